"""The health store: blood pressure, heart rate, steps and sleep per user (SQLAlchemy 2).

SQLite in WAL mode by default (``synchronous=FULL``: a write that returned survives a
crash of the process); any SQLAlchemy URL works, PostgreSQL included.  Times are UTC epoch
seconds plus the UTC day number, so "yesterday" and daily trends are indexed range queries
that mean the same on every database.
"""

from __future__ import annotations

from dataclasses import dataclass
from datetime import UTC, date, datetime, timedelta
from typing import Any

import numpy as np
from sqlalchemy import (
    Engine,
    Float,
    Index,
    Integer,
    String,
    create_engine,
    event,
    func,
    insert,
    select,
)
from sqlalchemy.exc import ArgumentError, DBAPIError
from sqlalchemy.orm import DeclarativeBase, Mapped, mapped_column
from sqlalchemy.pool import StaticPool

from amiro.core.config import ConfigError
from amiro.environment.messages import HealthMeasurement

EPOCH_DAY = date(1970, 1, 1)
STABLE_SLOPE = 0.005  # |slope| per day below this share of the mean: "stable"


class Base(DeclarativeBase):
    pass


class MeasurementRow(Base):
    __tablename__ = "health_measurements"
    id: Mapped[int] = mapped_column(Integer, primary_key=True, autoincrement=True)
    user: Mapped[str] = mapped_column(String(40))
    metric: Mapped[str] = mapped_column(String(20))
    ts: Mapped[float] = mapped_column(Float)
    day: Mapped[int] = mapped_column(Integer)
    value: Mapped[float] = mapped_column(Float)
    value2: Mapped[float | None] = mapped_column(Float, nullable=True)
    __table_args__ = (
        Index("ix_health_user_metric_ts", "user", "metric", "ts"),
        Index("ix_health_user_metric_day", "user", "metric", "day"),
    )


MEMORY = "sqlite://"


def open_engine(url: str | None) -> Engine:
    """An engine for ``url`` (None: one in-memory SQLite database shared by all threads);
    SQLite files get WAL, full sync and a busy timeout."""
    if url is None or url == MEMORY:
        engine = create_engine(
            MEMORY, poolclass=StaticPool, connect_args={"check_same_thread": False}
        )
        Base.metadata.create_all(engine)
        return engine
    try:
        engine = create_engine(url)
    except (ArgumentError, ImportError) as exc:
        raise ConfigError(f"database '{url}': {exc}") from None
    if engine.dialect.name == "sqlite":

        @event.listens_for(engine, "connect")
        def _pragmas(dbapi_conn: Any, _record: Any) -> None:
            cur = dbapi_conn.cursor()
            cur.execute("PRAGMA journal_mode=WAL")
            cur.execute("PRAGMA synchronous=FULL")
            cur.execute("PRAGMA busy_timeout=5000")
            cur.close()

    try:
        Base.metadata.create_all(engine)
    except DBAPIError as exc:  # a missing folder, no permission, a server that is not there
        engine.dispose()
        reason = " ".join(str(exc.orig).split())  # psycopg's message has several lines
        raise ConfigError(f"database '{url}': cannot open it: {reason}") from None
    return engine


def to_epoch(ts: str) -> float:
    """ISO 8601 → UTC epoch seconds (a naive timestamp is taken as UTC)."""
    moment = datetime.fromisoformat(ts)
    if moment.tzinfo is None:
        moment = moment.replace(tzinfo=UTC)
    return moment.timestamp()


def day_number(day: date) -> int:
    return (day - EPOCH_DAY).days


@dataclass(frozen=True)
class Reading:
    metric: str
    value: float
    value2: float | None
    ts: str

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {"metric": self.metric, "ts": self.ts}
        if self.metric == "blood_pressure":
            out |= {"systolic": self.value, "diastolic": self.value2}
        else:
            out["value"] = self.value
        return out


@dataclass(frozen=True)
class DaySummary:
    day: str
    count: int
    mean: float | None
    minimum: float | None
    maximum: float | None
    total: float | None
    mean2: float | None  # diastolic mean for blood pressure

    def to_dict(self) -> dict[str, Any]:
        return {
            "day": self.day,
            "count": self.count,
            "mean": self.mean,
            "min": self.minimum,
            "max": self.maximum,
            "total": self.total,
            "mean2": self.mean2,
        }


@dataclass(frozen=True)
class Trend:
    days: list[DaySummary]
    slope_per_day: float
    direction: str  # rising | falling | stable | unknown

    def to_dict(self) -> dict[str, Any]:
        return {
            "days": [d.to_dict() for d in self.days],
            "slope_per_day": self.slope_per_day,
            "direction": self.direction,
        }


# Steps and sleep add up over a day; heart rate and blood pressure average.
ADDITIVE = {"steps", "sleep"}


class HealthStore:
    def __init__(self, url: str | None = None) -> None:
        self.engine = open_engine(url)

    def close(self) -> None:
        self.engine.dispose()

    def add(self, m: HealthMeasurement) -> int:
        """Store one measurement; when this returns it is committed (durable)."""
        return self.add_many([m])

    def add_many(self, items: list[HealthMeasurement]) -> int:
        """Store measurements in one transaction; returns how many."""
        rows = []
        for m in items:
            ts = to_epoch(m.ts)
            rows.append(
                {
                    "user": m.user,
                    "metric": m.metric,
                    "ts": ts,
                    "day": int(ts // 86400),
                    "value": m.value,
                    "value2": m.value2,
                }
            )
        if rows:
            with self.engine.begin() as conn:
                conn.execute(insert(MeasurementRow), rows)
        return len(rows)

    def count(self, user: str | None = None) -> int:
        query = select(func.count()).select_from(MeasurementRow)
        if user is not None:
            query = query.where(MeasurementRow.user == user)
        with self.engine.connect() as conn:
            return int(conn.execute(query).scalar_one())

    def users(self) -> list[str]:
        with self.engine.connect() as conn:
            rows = conn.execute(
                select(MeasurementRow.user).distinct().order_by(MeasurementRow.user)
            )
            return [r[0] for r in rows]

    def latest(self, user: str, metric: str) -> Reading | None:
        row = MeasurementRow
        query = (
            select(row.value, row.value2, row.ts)
            .where(row.user == user, row.metric == metric)
            .order_by(row.ts.desc())
            .limit(1)
        )
        with self.engine.connect() as conn:
            found = conn.execute(query).first()
        if found is None:
            return None
        iso = datetime.fromtimestamp(found.ts, UTC).isoformat(timespec="seconds")
        return Reading(metric, found.value, found.value2, iso)

    def daily(self, user: str, metric: str, first: date, last: date) -> list[DaySummary]:
        """One summary per day from ``first`` to ``last`` (inclusive), empty days included."""
        row = MeasurementRow
        query = (
            select(
                row.day,
                func.count(),
                func.avg(row.value),
                func.min(row.value),
                func.max(row.value),
                func.sum(row.value),
                func.avg(row.value2),
            )
            .where(
                row.user == user,
                row.metric == metric,
                row.day >= day_number(first),
                row.day <= day_number(last),
            )
            .group_by(row.day)
        )
        with self.engine.connect() as conn:
            found = {r[0]: r for r in conn.execute(query)}
        out = []
        for n in range(day_number(first), day_number(last) + 1):
            label = (EPOCH_DAY + timedelta(days=n)).isoformat()
            r = found.get(n)
            if r is None:
                out.append(DaySummary(label, 0, None, None, None, None, None))
            else:
                out.append(DaySummary(label, int(r[1]), *(_f(v) for v in r[2:])))
        return out

    def day(self, user: str, metric: str, day: date) -> DaySummary:
        return self.daily(user, metric, day, day)[0]

    def yesterday(self, user: str, metric: str, today: date) -> DaySummary:
        return self.day(user, metric, today - timedelta(days=1))

    def trend(self, user: str, metric: str, last: date, days: int = 7) -> Trend:
        """Daily values over ``days`` days ending ``last`` and their least-squares slope."""
        summaries = self.daily(user, metric, last - timedelta(days=days - 1), last)
        key = "total" if metric in ADDITIVE else "mean"
        points = [(i, getattr(s, key)) for i, s in enumerate(summaries) if s.count]
        if len(points) < 2:
            return Trend(summaries, 0.0, "unknown")
        xs, ys = np.array([p[0] for p in points], float), np.array([p[1] for p in points], float)
        slope = float(np.polyfit(xs, ys, 1)[0])
        scale = max(abs(float(ys.mean())), 1e-9)
        if abs(slope) < STABLE_SLOPE * scale:
            direction = "stable"
        else:
            direction = "rising" if slope > 0 else "falling"
        return Trend(summaries, round(slope, 4), direction)


def _f(value: Any) -> float | None:
    return None if value is None else round(float(value), 3)
