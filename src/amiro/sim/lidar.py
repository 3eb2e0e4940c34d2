"""A 360-degree lidar like the RPLidar A1 the AMIRO robot carries, ray cast on a grid.

All beams are cast at once: a coarse pass samples every ray at one-cell steps and finds the
first occupied sample, then a fine pass samples the last interval of each hit beam to place
the return within a fraction of a cell.  Ranges follow REP-117: ``+inf`` for no return
within ``range_max``, ``-inf`` for a return closer than ``range_min``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from amiro.core.gridmap import GridMap
from amiro.core.messages import Header, LaserScan, Pose2D

FloatArray = npt.NDArray[np.float64]

_FINE_STEPS = 8


@dataclass(frozen=True, slots=True)
class LidarParams:
    beams: int = 360
    range_min: float = 0.15
    range_max: float = 12.0
    rate: float = 10.0  # Hz, RPLidar A1 spins at 5.5-10 Hz
    noise: float = 0.01  # range noise sigma as a fraction of the range
    frame_id: str = "laser"

    def __post_init__(self) -> None:
        if not 5.5 <= self.rate <= 10.0:
            raise ValueError(f"lidar rate must be within 5.5..10 Hz, got {self.rate}")
        if self.beams < 1 or not 0.0 < self.range_min < self.range_max:
            raise ValueError("lidar needs beams >= 1 and 0 < range_min < range_max")


class Lidar:
    """Casts ``beams`` rays over 360 degrees, counter-clockwise from the robot's heading."""

    def __init__(self, params: LidarParams | None = None) -> None:
        self.params = p = params or LidarParams()
        self.angle_increment = 2.0 * math.pi / p.beams
        self.angles: FloatArray = -math.pi + self.angle_increment * np.arange(
            p.beams, dtype=np.float64
        )

    def true_ranges(self, grid: GridMap, pose: Pose2D) -> FloatArray:
        """Noise-free distance to the first occupied cell per beam (``inf`` if none)."""
        p = self.params
        res = grid.resolution
        # only sample as far as the map reaches from here
        corners_x = grid.origin[0] + np.array([0.0, grid.width, 0.0, grid.width]) * res
        corners_y = grid.origin[1] + np.array([0.0, 0.0, grid.height, grid.height]) * res
        reach = float(np.max(np.hypot(corners_x - pose.x, corners_y - pose.y)))
        if grid.origin[2] != 0.0:
            reach = p.range_max
        r_max = min(p.range_max, reach)
        steps = np.arange(res * 0.5, r_max + res, res)  # coarse samples along every ray
        th = pose.theta + self.angles
        cos, sin = np.cos(th), np.sin(th)
        occ = grid.data != 0  # occupied or unknown stop the beam
        hit_any, first = self._first_hit(grid, occ, pose, cos, sin, steps)
        ranges = np.full(p.beams, np.inf)
        if not hit_any.any():
            return ranges
        b = np.nonzero(hit_any)[0]
        k = first[b]
        lo = np.where(k > 0, steps[np.maximum(k - 1, 0)], 0.0)
        hi = steps[k]
        frac = np.arange(1, _FINE_STEPS + 1) / _FINE_STEPS
        fine = lo[:, None] + (hi - lo)[:, None] * frac[None, :]
        fx = pose.x + fine * cos[b, None]
        fy = pose.y + fine * sin[b, None]
        col, row = grid.world_to_cell(fx, fy)
        inside = grid.in_bounds(col, row)
        hit = np.zeros(fine.shape, dtype=bool)
        hit[inside] = occ[row[inside], col[inside]]
        j = np.argmax(hit, axis=1)  # a coarse hit guarantees a fine hit at the last sample
        ranges[b] = fine[np.arange(len(b)), j] - 0.5 * (hi - lo) / _FINE_STEPS
        return ranges

    @staticmethod
    def _first_hit(
        grid: GridMap,
        occ: npt.NDArray[np.bool_],
        pose: Pose2D,
        cos: FloatArray,
        sin: FloatArray,
        steps: FloatArray,
    ) -> tuple[npt.NDArray[np.bool_], npt.NDArray[np.intp]]:
        res = grid.resolution
        ox, oy = grid.origin[0], grid.origin[1]
        u: npt.NDArray[np.floating[Any]]
        v: npt.NDArray[np.floating[Any]]
        if grid.origin[2] == 0.0:
            st = steps.astype(np.float32) / np.float32(res)
            u = np.float32((pose.x - ox) / res) + np.outer(cos.astype(np.float32), st)
            v = np.float32((pose.y - oy) / res) + np.outer(sin.astype(np.float32), st)
        else:
            u, v = grid.world_to_map(pose.x + np.outer(cos, steps), pose.y + np.outer(sin, steps))
        # a one-cell free border lets out-of-map samples clip onto it instead of masking
        w, h = grid.width, grid.height
        padded = np.zeros((h + 2, w + 2), dtype=bool)
        padded[1:-1, 1:-1] = occ
        col = np.clip(np.floor(u), -1, w).astype(np.intp) + 1
        row = np.clip(np.floor(v), -1, h).astype(np.intp) + 1
        hits = padded.reshape(-1)[row * (w + 2) + col]
        first = np.argmax(hits, axis=1)
        return hits[np.arange(len(first)), first], first

    def scan(
        self, grid: GridMap, pose: Pose2D, stamp: float, rng: np.random.Generator | None = None
    ) -> LaserScan:
        """One scan from a lidar at ``pose`` (the base centre), with range noise if ``rng``."""
        p = self.params
        ranges = self.true_ranges(grid, pose)
        finite = np.isfinite(ranges)
        if rng is not None and p.noise > 0:
            ranges[finite] += p.noise * ranges[finite] * rng.standard_normal(int(finite.sum()))
        ranges[finite & (ranges > p.range_max)] = np.inf
        ranges[finite & (ranges < p.range_min)] = -np.inf
        return LaserScan(
            header=Header(stamp, p.frame_id),
            angle_min=float(self.angles[0]),
            angle_max=float(self.angles[-1]),
            angle_increment=self.angle_increment,
            time_increment=1.0 / (p.rate * p.beams),
            scan_time=1.0 / p.rate,
            range_min=p.range_min,
            range_max=p.range_max,
            ranges=ranges,
        )
