"""The dialogue's health answers from the health store (the dialogue's ``HealthSource``).

Today's blood pressure and heart rate are the latest reading of the day; steps and sleep
add up over the day.  Past days are daily means (or totals).  There is no answer for the
future, for a day without readings, or for a metric the store does not hold.
"""

from __future__ import annotations

from collections.abc import Callable
from datetime import date, datetime
from typing import Any

from amiro.environment.days import resolve_day
from amiro.environment.health_store import ADDITIVE, HealthStore
from amiro.environment.messages import HEALTH_METRICS


class StoreHealth:
    def __init__(self, store: HealthStore, today: Callable[[], date]) -> None:
        self.store = store
        self.today = today

    def latest(self, user: str, metric: str, day: str) -> dict[str, Any] | None:
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


def spoken_values(metric: str, value: float, value2: float | None) -> dict[str, Any]:
    """The phrase fields of a measurement, rounded as a person would say them."""
    if metric == "blood_pressure":
        return {"systolic": round(value), "diastolic": round(value2 or 0.0)}
    return {"value": round(value, 1) if metric == "sleep" else round(value)}
