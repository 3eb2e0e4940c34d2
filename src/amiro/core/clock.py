"""The one clock: simulated (deterministic, optionally paced) or wall time for real robots.

Nothing else in amiro reads wall time or sleeps; the executor asks the clock to move to the
next timer deadline, so a simulated run is as fast as the computation allows and repeatable.
"""

from __future__ import annotations

import time
from datetime import UTC, datetime, timedelta
from typing import Protocol

# Simulated time 0 is this calendar instant (a hot summer morning), so reminders and
# acknowledgements carry plausible ISO 8601 timestamps.
SIM_EPOCH = datetime(2026, 7, 15, 10, 0, 0, tzinfo=UTC)


class Clock(Protocol):
    def now(self) -> float:
        """Seconds since the clock's epoch."""
        ...

    def advance_to(self, t: float) -> None:
        """Move to time ``t`` (>= now): jump in simulation, wait on a real robot."""
        ...

    def iso(self, t: float) -> str:
        """Clock time ``t`` as an ISO 8601 UTC timestamp."""
        ...


class SimClock:
    """Simulated time starting at 0.

    ``speed=None`` runs as fast as the computation allows; ``speed=k`` paces simulated time
    at k times real time (for demos and the dashboard), never running ahead of it.
    """

    def __init__(
        self, speed: float | None = None, start: float = 0.0, epoch: datetime = SIM_EPOCH
    ) -> None:
        if speed is not None and speed <= 0:
            raise ValueError(f"clock speed must be positive, got {speed}")
        self._now = start
        self._speed = speed
        self._wall_origin = time.monotonic()
        self._sim_origin = start
        self.epoch = epoch

    def iso(self, t: float) -> str:
        return (self.epoch + timedelta(seconds=t)).isoformat(timespec="seconds")

    @property
    def speed(self) -> float | None:
        return self._speed

    def set_speed(self, speed: float | None) -> None:
        if speed is not None and speed <= 0:
            raise ValueError(f"clock speed must be positive, got {speed}")
        self._speed = speed
        self._wall_origin = time.monotonic()
        self._sim_origin = self._now

    def now(self) -> float:
        return self._now

    def advance_to(self, t: float) -> None:
        if t < self._now:
            return
        self._now = t
        if self._speed is not None:
            due = self._wall_origin + (t - self._sim_origin) / self._speed
            delay = due - time.monotonic()
            if delay > 0:
                time.sleep(delay)


class WallClock:
    """Real time, for a real robot: seconds since the Unix epoch."""

    def now(self) -> float:
        return time.time()

    def iso(self, t: float) -> str:
        return datetime.fromtimestamp(t, UTC).isoformat(timespec="seconds")

    def advance_to(self, t: float) -> None:
        delay = t - time.time()
        if delay > 0:
            time.sleep(delay)


def wall_seconds() -> float:
    """Monotonic wall time, only for measuring how long a computation took."""
    return time.perf_counter()
