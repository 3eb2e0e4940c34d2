"""Messages only the simulator speaks: ground truth for oracles and scoring, sim events."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True, slots=True)
class Collision:
    """The base touched an obstacle (one per new contact, not one per tick)."""

    stamp: float
    x: float
    y: float
    theta: float
    count: int
