"""Simulated CARMEN logs of loops around a generated office floor's corridor ring.

The SLAM evaluation needs long indoor logs with loops: the robot drives the centre line of
the ring corridor of a ``floorplan.generate_floor`` office several times, so every loop
revisits places seen before (loop closures) through long, self-similar corridors.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from amiro.navigation.floorplan import CORRIDOR_M, ROOM_DEPTH_M, generate_floor
from amiro.sim.carmen_log import write_log

RESOLUTION_M = 0.05


def ring_route(width_m: float, height_m: float, loops: int) -> list[tuple[float, float]]:
    """The ring corridor's centre line, counter-clockwise, ``loops`` times round."""
    a = ROOM_DEPTH_M + CORRIDOR_M / 2.0
    corners = [(a, a), (width_m - a, a), (width_m - a, height_m - a), (a, height_m - a)]
    return corners * loops + [corners[0]]


def route_length(route: list[tuple[float, float]]) -> float:
    xy = np.asarray(route, dtype=np.float64)
    return float(np.hypot(*np.diff(xy, axis=0).T).sum())


def write_office_log(
    path: Path,
    rng: np.random.Generator,
    width_m: float = 50.0,
    height_m: float = 60.0,
    loops: int = 3,
) -> int:
    """Generate a floor, drive ``loops`` laps of its ring and log them; returns the scans.

    50 x 60 m, 3 laps is the ~490 m evaluation log; 20 x 25 m, 3 laps (~100 m) the test log.
    """
    rng_floor, rng_drive = rng.spawn(2)
    grid = generate_floor(rng_floor, width_m, height_m, RESOLUTION_M)
    return write_log(path, grid, ring_route(width_m, height_m, loops), rng_drive)
