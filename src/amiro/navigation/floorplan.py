"""Generated building floor plans for the navigation benchmark (no real maps ship offline).

An office/hospital-like floor: a ring of corridors around a core, rooms of random widths on
both sides of every corridor, each with one door, and furniture blocks inside the rooms.
Seeded, so the shipped maps can be regenerated exactly.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable

import numpy as np

from amiro.core.gridmap import FREE, OCCUPIED, GridMap

WALL_M = 0.15
CORRIDOR_M = 2.4
ROOM_DEPTH_M = 6.0
DOOR_M = 1.1

Rect = tuple[float, float, float, float]


def generate_floor(
    rng: np.random.Generator,
    width_m: float = 50.0,
    height_m: float = 60.0,
    resolution: float = 0.05,
) -> GridMap:
    """A ``width_m`` x ``height_m`` floor at ``resolution`` m/cell (ROS conventions)."""
    rows, cols = round(height_m / resolution), round(width_m / resolution)
    occ = np.zeros((rows, cols), dtype=bool)

    def box(x0: float, y0: float, x1: float, y1: float, value: bool = True) -> None:
        r0, r1 = sorted((round(y0 / resolution), round(y1 / resolution)))
        c0, c1 = sorted((round(x0 / resolution), round(x1 / resolution)))
        occ[max(r0, 0) : min(r1, rows), max(c0, 0) : min(c1, cols)] = value

    def wall_x(y: float, x0: float, x1: float) -> None:
        box(x0, y - WALL_M / 2, x1, y + WALL_M / 2)

    def wall_y(x: float, y0: float, y1: float) -> None:
        box(x - WALL_M / 2, y0, x + WALL_M / 2, y1)

    # outer walls
    wall_x(WALL_M / 2, 0, width_m)
    wall_x(height_m - WALL_M / 2, 0, width_m)
    wall_y(WALL_M / 2, 0, height_m)
    wall_y(width_m - WALL_M / 2, 0, height_m)
    # corridor ring: outer rooms band, corridor, inner rooms band, core
    a, b = ROOM_DEPTH_M, ROOM_DEPTH_M + CORRIDOR_M  # corridor band from the outer wall
    inner: Rect = (b, b, width_m - b, height_m - b)
    outer: Rect = (a, a, width_m - a, height_m - a)
    for x0, y0, x1, y1 in (outer, inner):
        wall_x(y0, x0, x1)
        wall_x(y1, x0, x1)
        wall_y(x0, y0, y1)
        wall_y(x1, y0, y1)
    # a cross corridor through the core so there are loops
    mid = height_m / 2
    box(inner[0], mid - CORRIDOR_M / 2, inner[2], mid + CORRIDOR_M / 2, value=False)
    wall_x(mid - CORRIDOR_M / 2, inner[0], inner[2])
    wall_x(mid + CORRIDOR_M / 2, inner[0], inner[2])
    box(
        inner[0] - WALL_M,
        mid - CORRIDOR_M / 2 + WALL_M,
        inner[0] + WALL_M,
        mid + CORRIDOR_M / 2 - WALL_M,
        False,
    )
    box(
        inner[2] - WALL_M,
        mid - CORRIDOR_M / 2 + WALL_M,
        inner[2] + WALL_M,
        mid + CORRIDOR_M / 2 - WALL_M,
        False,
    )
    _rooms_along(rng, box, wall_x, wall_y, outer, inner, width_m, height_m, mid)
    data = np.where(occ, OCCUPIED, FREE).astype(np.int8)
    return GridMap(data, resolution, (0.0, 0.0, 0.0))


def _rooms_along(
    rng: np.random.Generator,
    box: Callable[..., None],
    wall_x: Callable[[float, float, float], None],
    wall_y: Callable[[float, float, float], None],
    outer: Rect,
    inner: Rect,
    width_m: float,
    height_m: float,
    mid: float,
) -> None:
    """Partition walls every 3.5-6 m in the outer band and the core, a door into the
    corridor for each room, and a couple of furniture blocks per room."""

    def split(lo: float, hi: float) -> list[float]:
        cuts, x = [lo], lo
        while hi - x > 7.0:
            x += float(rng.uniform(3.5, 6.0))
            cuts.append(x)
        cuts.append(hi)
        return cuts

    # (span axis, band lo..hi across, corridor-side wall position, along range)
    bands = [
        ("x", 0.0, outer[1], outer[1], (0.0, width_m)),
        ("x", outer[3], height_m, outer[3], (0.0, width_m)),
        ("y", 0.0, outer[0], outer[0], (outer[1], outer[3])),
        ("y", outer[2], width_m, outer[2], (outer[1], outer[3])),
        ("x", inner[1], mid - CORRIDOR_M / 2, inner[1], (inner[0], inner[2])),
        ("x", mid + CORRIDOR_M / 2, inner[3], inner[3], (inner[0], inner[2])),
    ]
    for axis, lo, hi, door_at, (a0, a1) in bands:
        cuts = split(a0, a1)
        for c0, c1 in itertools.pairwise(cuts):
            if axis == "x":
                wall_y(c1, lo, hi)
            else:
                wall_x(c1, lo, hi)
            d = float(rng.uniform(c0 + 0.8, max(c0 + 0.9, c1 - DOOR_M - 0.8)))
            if axis == "x":
                box(d, door_at - 0.3, d + DOOR_M, door_at + 0.3, False)
            else:
                box(door_at - 0.3, d, door_at + 0.3, d + DOOR_M, False)
            for _ in range(int(rng.integers(1, 3))):
                w, h = float(rng.uniform(0.6, 1.6)), float(rng.uniform(0.5, 1.0))
                u = float(rng.uniform(c0 + 0.3, max(c0 + 0.4, c1 - w - 0.3)))
                depth_lo, depth_hi = min(lo, hi), max(lo, hi)
                # keep the strip in front of the door free: furniture in the far half
                far = depth_lo + 0.3 if abs(door_at - depth_hi) < 1e-6 else depth_hi - h - 0.3
                if axis == "x":
                    box(u, far, u + w, far + h)
                else:
                    box(far, u, far + h, u + w)
