"""Import health data from CSV or JSON files into the :class:`HealthStore`.

CSV: a header with ``user,metric,ts`` and ``value`` (or ``systolic,diastolic`` for blood
pressure).  JSON: a list of such objects, or ``{"measurements": [...]}``.  Every row is
validated like an MQTT message; the first bad row stops the import with its line number.
"""

from __future__ import annotations

import csv
import json
from pathlib import Path
from typing import Any

from amiro.core.config import ConfigError, read_text
from amiro.environment.health_store import HealthStore
from amiro.environment.messages import HealthMeasurement
from amiro.environment.payloads import NAME, PayloadError, health_measurement

NUMERIC = ("value", "systolic", "diastolic")


def _row(record: Any, where: str) -> HealthMeasurement:
    if not isinstance(record, dict):
        raise ConfigError(f"{where}: expected an object with user, metric, ts and values")
    user, metric, ts = record.get("user"), record.get("metric"), record.get("ts")
    if not isinstance(user, str) or not NAME.match(user):
        raise ConfigError(f"{where}: 'user' must be 1-40 of a-z, 0-9, _")
    if not isinstance(metric, str) or not isinstance(ts, str) or not ts:
        raise ConfigError(f"{where}: 'metric' and 'ts' are required")
    fields: dict[str, Any] = {"ts": ts}
    for key in NUMERIC:
        raw = record.get(key)
        if raw in (None, ""):
            continue
        try:
            fields[key] = float(raw)
        except (TypeError, ValueError):
            raise ConfigError(f"{where}: '{key}' is not a number: {raw!r}") from None
    try:
        return health_measurement(user, metric, fields, ts)
    except PayloadError as exc:
        raise ConfigError(f"{where}: {exc}") from None


def read_measurements(path: str | Path) -> list[HealthMeasurement]:
    p = Path(path)
    text = read_text(p)
    if p.suffix.lower() == ".csv":
        reader = csv.DictReader(text.splitlines())
        return [_row(rec, f"{p}: line {i}") for i, rec in enumerate(reader, start=2)]
    if p.suffix.lower() == ".json":
        try:
            data = json.loads(text)
        except json.JSONDecodeError as exc:
            raise ConfigError(f"{p}: invalid JSON: {exc}") from None
        if isinstance(data, dict):
            data = data.get("measurements")
        if not isinstance(data, list):
            raise ConfigError(f"{p}: expected a list of measurements")
        return [_row(rec, f"{p}: item {i}") for i, rec in enumerate(data)]
    raise ConfigError(f"{p}: expected a .csv or .json file")


def import_file(store: HealthStore, path: str | Path) -> int:
    """Validate the whole file first, then store it in one transaction."""
    return store.add_many(read_measurements(path))
