"""Calendar days on the runtime clock: the simulated home has its own date, never the host's."""

from __future__ import annotations

from datetime import date, datetime, timedelta

from amiro.core.clock import Clock

RELATIVE_DAYS = {"yesterday": -1, "today": 0, "tomorrow": 1}


def clock_datetime(clock: Clock) -> datetime:
    """The runtime clock's current instant, timezone-aware (UTC)."""
    return datetime.fromisoformat(clock.iso(clock.now()))


def clock_date(clock: Clock) -> date:
    """Today's UTC date on the runtime clock (the health store's days are UTC days)."""
    return clock_datetime(clock).date()


def resolve_day(day: str, today: date) -> date | None:
    """The NLU's ``dateandtime_entity`` (today, tomorrow, yesterday or an ISO date) as a
    date; None when it is neither."""
    if day in RELATIVE_DAYS:
        return today + timedelta(days=RELATIVE_DAYS[day])
    try:
        return date.fromisoformat(day)
    except ValueError:
        return None
