"""The dialogue's health answers from the health store (the dialogue's ``HealthSource``).

Today's blood pressure and heart rate are the latest reading of the day; steps and sleep
add up over the day.  Past days are daily means (or totals).  There is no answer for the
future, for a day without readings, or for a metric the store does not hold.

"How am I?" (``health_status``) checks the day's blood pressure and heart rate against the
user's health rules (the same thresholds that alert the carers), or against common
reference ranges for a metric no rule covers, and names the first reading out of range.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from datetime import date, datetime
from typing import Any

from amiro.environment.days import resolve_day
from amiro.environment.health_store import ADDITIVE, HealthStore
from amiro.environment.messages import HEALTH_METRICS
from amiro.environment.rules import HealthRule

STATUS = "health_status"
STATUS_METRICS = ("blood_pressure", "heart_rate")
# Resting adult ranges (hypertension from 140/90, hypotension below 90 systolic; heart rate
# outside 50–100 bpm): used for a metric the user has no health rule for.
REFERENCE_RANGES = (
    HealthRule(name="systolic", metric="blood_pressure", above=140, below=90),
    HealthRule(name="diastolic", metric="blood_pressure", diastolic=True, above=90),
    HealthRule(name="heart_rate", metric="heart_rate", above=100, below=50),
)


class StoreHealth:
    def __init__(
        self, store: HealthStore, today: Callable[[], date], rules: Sequence[HealthRule] = ()
    ) -> None:
        self.store = store
        self.today = today
        self.rules = tuple(rules)

    def latest(self, user: str, metric: str, day: str) -> dict[str, Any] | None:
        if metric == STATUS:
            return self.status(user, day)
        today = self.today()
        when = resolve_day(day, today)
        if metric not in HEALTH_METRICS or when is None or when > today:
            return None
        if when == today and metric not in ADDITIVE:
            reading = self.store.latest(user, metric)
            if reading is None or datetime.fromisoformat(reading.ts).date() != today:
                return None
            return spoken_values(metric, reading.value, reading.value2)
        summary = self.store.day(user, metric, when)
        value = summary.total if metric in ADDITIVE else summary.mean
        if not summary.count or value is None:
            return None
        return spoken_values(metric, value, summary.mean2)

    def status(self, user: str, day: str) -> dict[str, Any] | None:
        """``{"status": "ok"}``, or ``"attention"`` with the first reading out of range;
        None when the day has no blood pressure or heart rate reading."""
        readings = {m: self.latest(user, m, day) for m in STATUS_METRICS}
        if all(values is None for values in readings.values()):
            return None
        for metric, values in readings.items():
            if values is not None and any(
                rule.triggered(_checked_value(rule, values)) for rule in self._rules(user, metric)
            ):
                return {"status": "attention", "metric": metric, **values}
        return {"status": "ok"}

    def _rules(self, user: str, metric: str) -> list[HealthRule]:
        own = [r for r in self.rules if r.metric == metric and r.user in ("", user)]
        return own or [r for r in REFERENCE_RANGES if r.metric == metric]


def _checked_value(rule: HealthRule, values: dict[str, Any]) -> float:
    if rule.metric == "blood_pressure":
        return float(values["diastolic" if rule.diastolic else "systolic"])
    return float(values["value"])


def spoken_values(metric: str, value: float, value2: float | None) -> dict[str, Any]:
    """The phrase fields of a measurement, rounded as a person would say them."""
    if metric == "blood_pressure":
        return {"systolic": round(value), "diastolic": round(value2 or 0.0)}
    return {"value": round(value, 1) if metric == "sleep" else round(value)}
