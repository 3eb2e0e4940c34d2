"""The command line: --version, --help everywhere, one-line errors with exit code 2."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from amiro import __version__
from amiro.cli import main


def amiro(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "amiro.cli", *args],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )


def test_version(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exc:
        main(["--version"])
    assert exc.value.code == 0
    assert capsys.readouterr().out.strip() == f"amiro {__version__}"


@pytest.mark.parametrize(
    "command", [[], ["run"], ["run", "hydration"], ["bench"], ["bench", "core"]]
)
def test_every_command_has_help(command: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exc:
        main([*command, "--help"])
    assert exc.value.code == 0
    assert "usage: amiro" in capsys.readouterr().out


def one_line_error(proc: subprocess.CompletedProcess[str]) -> str:
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, proc.stderr
    return lines[0]


def test_unknown_language_is_a_one_line_error() -> None:
    line = one_line_error(amiro("run", "hydration", "--headless", "--lang", "de"))
    assert "unknown language 'de'" in line


def test_missing_config_file(tmp_path: Path) -> None:
    line = one_line_error(
        amiro("run", "hydration", "--headless", "--config", str(tmp_path / "nope.yaml"))
    )
    assert "no such file" in line


@pytest.mark.parametrize(
    ("content", "expected"),
    [
        ("seed: [1, 2\n", "line"),
        ("sim:\n  lidar:\n    rate: 50\n", "sim.lidar.rate"),
        ("navigation:\n  speed_of_light: 3\n", "navigation.speed_of_light"),
        ("sim:\n  residents:\n    - {name: ana, at: nowhere}\n", "nowhere"),
        ("behavior:\n  handlers:\n    hydration: /no/such/behaviour.yaml\n", "no such file"),
    ],
)
def test_bad_config_is_a_one_line_error(tmp_path: Path, content: str, expected: str) -> None:
    path = tmp_path / "bad.yaml"
    path.write_text(content)
    line = one_line_error(amiro("run", "hydration", "--headless", "--config", str(path)))
    assert expected in line


def test_usage_errors_exit_2() -> None:
    proc = amiro("run", "hydration", "--seed", "many")
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    proc = amiro("run", "hydration", "--unreachable", "--person-absent")
    assert proc.returncode == 2
