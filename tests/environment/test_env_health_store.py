"""The health store: the queries the dialogue needs, imports, and no loss under SIGKILL."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from datetime import date
from pathlib import Path

import pytest

from amiro.core.config import ConfigError
from amiro.environment.health_import import import_file
from amiro.environment.health_store import HealthStore
from amiro.environment.messages import HealthMeasurement


def hm(metric: str, value: float, ts: str, value2: float | None = None) -> HealthMeasurement:
    return HealthMeasurement("maria", metric, value, ts, value2)


def test_latest_yesterday_and_trend(database_url: str) -> None:
    store = HealthStore(database_url)
    store.add_many(
        [hm("steps", 1000.0, f"2026-07-14T{h:02d}:00:00+00:00") for h in range(8, 12)]
        + [hm("steps", 50.0, "2026-07-15T08:00:00+00:00")]
        + [hm("blood_pressure", 120.0 + d, f"2026-07-{d:02d}T08:00:00", 80.0) for d in range(8, 15)]
    )
    assert store.latest("maria", "steps").value == 50.0  # type: ignore[union-attr]
    assert store.latest("maria", "sleep") is None
    y = store.yesterday("maria", "steps", date(2026, 7, 15))
    assert (y.day, y.count, y.total) == ("2026-07-14", 4, 4000.0)
    bp = store.latest("maria", "blood_pressure")
    assert (
        bp is not None and bp.to_dict()["systolic"] == 134.0 and bp.to_dict()["diastolic"] == 80.0
    )
    trend = store.trend("maria", "blood_pressure", date(2026, 7, 14), 7)
    assert trend.direction == "rising" and trend.slope_per_day == pytest.approx(1.0)
    flat = store.trend("maria", "steps", date(2026, 7, 15), 3)
    assert flat.direction == "falling" and [d.count for d in flat.days] == [0, 4, 1]
    assert store.trend("maria", "sleep", date(2026, 7, 15)).direction == "unknown"
    assert store.users() == ["maria"] and store.count("bob") == 0
    store.close()


def test_import_csv_and_json_validates_every_row(tmp_path: Path) -> None:
    store = HealthStore()
    csv_file = tmp_path / "h.csv"
    csv_file.write_text(
        "user,metric,ts,value,systolic,diastolic\n"
        "ion,heart_rate,2026-07-01T08:00:00,71,,\n"
        "ion,blood_pressure,2026-07-01T08:00:00,,131,85\n"
    )
    assert import_file(store, csv_file) == 2
    js = tmp_path / "h.json"
    js.write_text(
        json.dumps(
            {
                "measurements": [
                    {"user": "ion", "metric": "sleep", "ts": "2026-07-01T07:00:00", "value": 6.5}
                ]
            }
        )
    )
    assert import_file(store, js) == 1
    assert store.count("ion") == 3
    bad = tmp_path / "bad.csv"
    bad.write_text(
        "user,metric,ts,value\nion,heart_rate,2026-07-01T08:00:00,71\nion,heart_rate,yesterday,70\n"
    )
    with pytest.raises(ConfigError, match=r"bad.csv: line 3: 'ts'"):
        import_file(store, bad)
    assert store.count("ion") == 3  # nothing of the bad file was stored
    with pytest.raises(ConfigError, match="no such file"):
        import_file(store, tmp_path / "missing.csv")


WRITER = """
import sys
from amiro.environment.health_store import HealthStore
from amiro.environment.messages import HealthMeasurement
store = HealthStore(sys.argv[1])
for i in range(1000):
    ts = f"2026-07-15T10:{i // 60 % 60:02d}:{i % 60:02d}"
    store.add(HealthMeasurement("maria", "heart_rate", 60 + i % 40, ts))
    print(i, flush=True)
"""


def test_sigkill_in_the_middle_of_1000_writes_loses_no_acknowledged_record(
    database_url: str,
) -> None:
    url = database_url
    proc = subprocess.Popen([sys.executable, "-c", WRITER, url], stdout=subprocess.PIPE, text=True)
    assert proc.stdout is not None
    acked = -1
    for line in proc.stdout:
        acked = int(line)
        if acked >= 400:
            break
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait(timeout=10)
    acked = max([acked, *(int(x) for x in proc.stdout.read().split())])
    assert 400 <= acked < 999  # killed in the middle
    store = HealthStore(url)
    stored = store.count("maria")
    assert stored >= acked + 1  # every acknowledged write survived (one more may have)
    assert stored <= acked + 2
    store.close()


def test_a_database_that_cannot_be_opened_is_one_line_and_exit_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from amiro.cli import main

    url = f"sqlite:///{tmp_path}/no/such/dir/h.db"
    with pytest.raises(ConfigError, match="cannot open it: unable to open database file"):
        HealthStore(url)
    assert main(["serve", "--db", url, "--port", "0"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err and url in err
