"""Occupancy grid mapping with log-odds updates, and the smooth map lookups scan matching needs.

Each scan lowers the log-odds of the cells its beams cross and raises those where they end;
the probability ``1 - 1 / (1 + e^l)`` is read back with bilinear interpolation and its
gradient, as Hector SLAM does (Kohlbrecher et al. 2011).
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from amiro.core.gridmap import FREE, OCCUPIED, UNKNOWN, GridMap
from amiro.navigation.scan_kernels import integrate_beams

FloatArray = npt.NDArray[np.float64]

L_OCC = 0.85
L_FREE = -0.4
L_CLAMP = 6.0


class LogOddsGrid:
    """A square-celled log-odds grid with its lower-left corner at ``origin`` (map frame)."""

    def __init__(
        self,
        width_m: float,
        height_m: float,
        resolution: float,
        origin: tuple[float, float],
        free_margin: float = 0.0,
        clamp: float = L_CLAMP,
    ) -> None:
        self.resolution = resolution
        # log-odds bound: how many contrary observations it takes to change a cell's mind
        self.clamp = clamp
        # beams are free only up to this fraction of their length short of the hit (at least
        # a cell): with range noise, beams that overshoot would otherwise erase the near face
        # of walls seen from afar, and the map (then the pose) would slide along corridors
        self.free_margin = free_margin
        self.origin = origin
        shape = (round(height_m / resolution), round(width_m / resolution))
        self.logodds = np.zeros(shape, np.float32)
        self.prob = np.full(shape, 0.5, np.float32)  # kept in step with the log-odds
        self._mark = np.zeros(shape, np.uint8)  # scratch of ``integrate``, all zero between

    def crop(self, r0: int, r1: int, c0: int, c1: int) -> None:
        """Keep rows r0..r1-1 and columns c0..c1-1 (the origin moves with them)."""
        self.logodds = self.logodds[r0:r1, c0:c1].copy()
        self.prob = self.prob[r0:r1, c0:c1].copy()
        self._mark = self._mark[r0:r1, c0:c1].copy()
        res = self.resolution
        self.origin = (self.origin[0] + c0 * res, self.origin[1] + r0 * res)

    def integrate(self, x: float, y: float, hx: FloatArray, hy: FloatArray) -> None:
        """Beams from (x, y) ending at hits (hx, hy): free along, occupied at the end."""
        if hx.size == 0:
            return
        res = self.resolution
        longest = float(np.max(np.hypot(hx - x, hy - y)))
        bound = hx.size * (int(np.ceil(longest / res)) + 1)
        changed = np.empty(min(bound, self.logodds.size), np.int64)
        count = integrate_beams(
            self.logodds,
            self._mark,
            x,
            y,
            np.ascontiguousarray(hx, np.float64),
            np.ascontiguousarray(hy, np.float64),
            self.origin[0],
            self.origin[1],
            res,
            self.free_margin,
            L_FREE,
            L_OCC,
            self.clamp,
            changed,
        )
        cells = changed[:count]
        self.prob.reshape(-1)[cells] = 1.0 - 1.0 / (1.0 + np.exp(self.logodds.reshape(-1)[cells]))

    def to_gridmap(self) -> GridMap:
        data = np.full(self.logodds.shape, UNKNOWN, dtype=np.int8)
        data[self.logodds < -0.5] = FREE
        data[self.logodds > 0.5] = OCCUPIED
        return GridMap(data, self.resolution, (self.origin[0], self.origin[1], 0.0))


def bilinear(
    prob: npt.NDArray[np.float32], u: FloatArray, v: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Value and gradient (d/du, d/dv, per cell) of a grid at continuous cell coordinates,
    where (u, v) = (0.5, 0.5) is the centre of cell (0, 0); out of range reads 0."""
    h, w = prob.shape
    u = u - 0.5
    v = v - 0.5
    c0 = np.floor(u).astype(np.intp)
    r0 = np.floor(v).astype(np.intp)
    fu, fv = u - c0, v - r0
    ok = (c0 >= 0) & (c0 < w - 1) & (r0 >= 0) & (r0 < h - 1)
    c0 = np.where(ok, c0, 0)
    r0 = np.where(ok, r0, 0)
    p00 = prob[r0, c0]
    p01 = prob[r0, c0 + 1]
    p10 = prob[r0 + 1, c0]
    p11 = prob[r0 + 1, c0 + 1]
    val = (1 - fv) * ((1 - fu) * p00 + fu * p01) + fv * ((1 - fu) * p10 + fu * p11)
    du = (1 - fv) * (p01 - p00) + fv * (p11 - p10)
    dv = (1 - fu) * (p10 - p00) + fu * (p11 - p01)
    zero = np.zeros_like(val)
    return np.where(ok, val, zero), np.where(ok, du, zero), np.where(ok, dv, zero)
