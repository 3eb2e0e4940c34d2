"""Vectorised planar geometry for rasterising and querying the simulated home."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]
BoolArray = npt.NDArray[np.bool_]
Vec2 = tuple[float, float]


def points_in_polygon(
    x: npt.ArrayLike, y: npt.ArrayLike, polygon: Sequence[Vec2] | FloatArray
) -> BoolArray:
    """Even-odd rule for many points at once (boundary points may go either way)."""
    px = np.asarray(x, dtype=np.float64)
    py = np.asarray(y, dtype=np.float64)
    poly = np.asarray(polygon, dtype=np.float64)
    inside = np.zeros(np.broadcast(px, py).shape, dtype=bool)
    n = len(poly)
    for i in range(n):
        x1, y1 = poly[i]
        x2, y2 = poly[(i + 1) % n]
        if y1 == y2:
            continue
        crosses = (y1 > py) != (y2 > py)
        x_at = x1 + (py - y1) * (x2 - x1) / (y2 - y1)
        inside ^= crosses & (px < x_at)
    return inside


def thick_segment_mask(
    x: npt.ArrayLike,
    y: npt.ArrayLike,
    a: Vec2,
    b: Vec2,
    thickness: float,
    cap: float = 0.0,
) -> BoolArray:
    """Points within ``thickness/2`` of segment ab, extended by ``cap`` past each end.

    Square caps of half the thickness close wall corners; ``cap=0`` makes door openings
    and door panels meet the remaining wall exactly.
    """
    px = np.asarray(x, dtype=np.float64) - a[0]
    py = np.asarray(y, dtype=np.float64) - a[1]
    dx, dy = b[0] - a[0], b[1] - a[1]
    length = math.hypot(dx, dy)
    if length == 0.0:
        return np.hypot(px, py) <= thickness / 2.0
    ux, uy = dx / length, dy / length
    along = px * ux + py * uy
    across = np.abs(-px * uy + py * ux)
    return (along >= -cap) & (along <= length + cap) & (across <= thickness / 2.0)


def wrap_angle(a: float) -> float:
    """Angle in (-pi, pi]."""
    return math.atan2(math.sin(a), math.cos(a))
