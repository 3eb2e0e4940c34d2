"""What the health charts need beyond the store: units, reference ranges, and demo data.

Reference ranges are the usual adult ones, shaded behind the charts as a guide, not a
diagnosis: blood pressure below 120/80 mmHg (ESC/ESH 2018 "optimal"; 90 and 60 as the
lower bounds), resting heart rate 60-100 bpm (AHA), 6,000-8,000 steps a day for people over
60 (Paluch et al., Lancet Public Health 2022), 7-8 hours of sleep for people over 65
(National Sleep Foundation, 2015).

Demo data: ``amiro serve`` with the default in-memory store starts with 14 days of
plausible, seeded measurements for each resident (``web.demo_data``, on by default), so a
first look at the dashboard shows charts; the API marks them ``demo`` and the page says so.
A database URL is a real household's store: nothing is ever seeded into it.
"""

from __future__ import annotations

from datetime import UTC, date, datetime, time, timedelta
from typing import Any

import numpy as np

from amiro.environment.health_store import HealthStore
from amiro.environment.messages import HealthMeasurement

METRIC_INFO: dict[str, dict[str, Any]] = {
    "blood_pressure": {
        "unit": "mmHg",
        "series": ["systolic", "diastolic"],
        "ranges": {"systolic": [90, 120], "diastolic": [60, 80]},
    },
    "heart_rate": {"unit": "bpm", "series": ["value"], "ranges": {"value": [60, 100]}},
    "steps": {"unit": "steps", "series": ["value"], "ranges": {"value": [6000, 8000]}},
    "sleep": {"unit": "h", "series": ["value"], "ranges": {"value": [7, 8]}},
}
DEMO_DAYS = 14


def demo_measurements(users: list[str], now: datetime, seed: int = 1) -> list[HealthMeasurement]:
    """``DEMO_DAYS`` days up to ``now`` for each user (none later): blood pressure and heart
    rate twice a day, steps and sleep once; a gentle drift so the trends say something."""
    rng = np.random.default_rng(seed)
    out: list[HealthMeasurement] = []
    today = now.date()

    def at(day: date, hour: int) -> str:
        return datetime.combine(day, time(hour), UTC).isoformat()

    for k, user in enumerate(users):
        base_sys, base_hr = 128.0 + 6 * k, 70.0 + 3 * k
        for n in range(DEMO_DAYS):
            day = today - timedelta(days=DEMO_DAYS - 1 - n)
            drift = 0.6 * n
            for hour in (8, 19):
                sys_ = base_sys + drift + rng.normal(0, 4)
                dia = 0.62 * sys_ + rng.normal(0, 3)
                out.append(
                    HealthMeasurement(
                        user, "blood_pressure", round(sys_), at(day, hour), round(dia)
                    )
                )
                hr = base_hr + rng.normal(0, 4)
                out.append(HealthMeasurement(user, "heart_rate", round(hr), at(day, hour)))
            steps = max(0.0, 5200 + 120 * n + rng.normal(0, 900))
            out.append(HealthMeasurement(user, "steps", round(steps), at(day, 21)))
            sleep = float(np.clip(6.8 + rng.normal(0, 0.6), 4.0, 9.5))
            out.append(HealthMeasurement(user, "sleep", round(sleep, 1), at(day, 7)))
    return [m for m in out if datetime.fromisoformat(m.ts) <= now]


def seed_demo(store: HealthStore, users: list[str], now: datetime, seed: int = 1) -> bool:
    """Fill an empty store with demo data; False (nothing written) when it holds any."""
    if store.count() or not users:
        return False
    store.add_many(demo_measurements(users, now, seed))
    return True
