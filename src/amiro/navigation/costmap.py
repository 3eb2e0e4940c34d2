"""Costmaps: the static map inflated by the robot's footprint, plus what the lidar sees.

Cells closer to an obstacle than the robot radius plus a safety margin are lethal; beyond
that a cost decays with distance, so planned paths keep a wide berth (Pepper's arms swing
outside its base footprint).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from scipy import ndimage

from amiro.core.messages import LaserScan, Pose2D

BoolGrid = npt.NDArray[np.bool_]
FloatGrid = npt.NDArray[np.float64]


@dataclass
class GridFrame:
    """Where a grid sits in the map frame: cell (row 0, col 0) has its corner at origin."""

    resolution: float
    origin_x: float
    origin_y: float
    height: int
    width: int

    def to_cell(self, x: float, y: float) -> tuple[int, int]:
        return (
            int(np.floor((y - self.origin_y) / self.resolution)),
            int(np.floor((x - self.origin_x) / self.resolution)),
        )

    def to_world(self, row: int, col: int) -> tuple[float, float]:
        return (
            self.origin_x + (col + 0.5) * self.resolution,
            self.origin_y + (row + 0.5) * self.resolution,
        )

    def inside(self, row: int, col: int) -> bool:
        return 0 <= row < self.height and 0 <= col < self.width


def downsample(occupied: BoolGrid, factor: int) -> BoolGrid:
    """Coarser grid where a cell is occupied if any of its fine cells is."""
    if factor <= 1:
        return occupied
    h = -(-occupied.shape[0] // factor) * factor
    w = -(-occupied.shape[1] // factor) * factor
    padded = np.zeros((h, w), dtype=bool)
    padded[: occupied.shape[0], : occupied.shape[1]] = occupied
    coarse = padded.reshape(h // factor, factor, w // factor, factor).any(axis=(1, 3))
    return np.asarray(coarse, dtype=bool)


class Costmap:
    """Static layer + observed-obstacle layer, inflated into lethal cells and a soft cost."""

    def __init__(
        self,
        static: BoolGrid,
        frame: GridFrame,
        robot_radius: float = 0.25,
        safety_margin: float = 0.1,
        decay_m: float = 0.35,
        hit_tolerance: float = 0.2,
    ) -> None:
        self.frame = frame
        self.static = static.copy()
        self.observed = np.zeros_like(static)
        self.robot_radius = robot_radius
        self.safety_margin = safety_margin
        self.decay_m = decay_m
        # lidar hits this close to a mapped obstacle are that obstacle seen with range noise
        self.hit_tolerance = hit_tolerance
        self._dirty = True
        self._lethal: BoolGrid = np.zeros_like(static)
        self._cost: FloatGrid = np.zeros(static.shape)
        self._clearance: FloatGrid = np.zeros(static.shape)
        self._static_clearance: FloatGrid = np.zeros(static.shape)
        self._gradient: tuple[FloatGrid, FloatGrid] = (self._cost, self._cost)

    def _update(self) -> None:
        obstacles = self.static | self.observed
        dist = ndimage.distance_transform_edt(~obstacles) * self.frame.resolution
        inscribed = self.inscribed
        self._clearance = dist
        static_dist = ndimage.distance_transform_edt(~self.static)
        self._static_clearance = static_dist * self.frame.resolution
        grad_rows, grad_cols = np.gradient(dist)
        self._gradient = (np.asarray(grad_cols), np.asarray(grad_rows))
        self._lethal = dist < inscribed
        self._cost = np.exp(-np.maximum(dist - inscribed, 0.0) / self.decay_m)
        self._dirty = False

    @property
    def clearance(self) -> FloatGrid:
        """Metres from each cell to the nearest known obstacle."""
        if self._dirty:
            self._update()
        return self._clearance

    @property
    def inscribed(self) -> float:
        return self.robot_radius + self.safety_margin

    def _cell(self, x: float, y: float) -> tuple[int, int] | None:
        cell = self.frame.to_cell(x, y)
        return cell if self.frame.inside(*cell) else None

    def clearance_at(self, x: float, y: float) -> float:
        """Metres from (x, y) to the nearest known obstacle (0 outside the map)."""
        if self._dirty:
            self._update()
        cell = self._cell(x, y)
        return 0.0 if cell is None else float(self._clearance[cell])

    def clearance_many(self, xs: FloatGrid, ys: FloatGrid) -> FloatGrid:
        """Vectorised :meth:`clearance_at` for arrays of points (0 outside the map)."""
        grid = self.clearance
        f = self.frame
        rows = np.floor((ys - f.origin_y) / f.resolution).astype(np.intp)
        cols = np.floor((xs - f.origin_x) / f.resolution).astype(np.intp)
        inside = (rows >= 0) & (rows < f.height) & (cols >= 0) & (cols < f.width)
        out = grid[np.clip(rows, 0, f.height - 1), np.clip(cols, 0, f.width - 1)]
        return np.where(inside, out, 0.0)

    def away_from_obstacles(self, x: float, y: float) -> tuple[float, float]:
        """Unit direction (map frame) in which clearance grows fastest; (0, 0) if flat."""
        if self._dirty:
            self._update()
        cell = self._cell(x, y)
        if cell is None:
            return 0.0, 0.0
        gx, gy = float(self._gradient[0][cell]), float(self._gradient[1][cell])
        norm = float(np.hypot(gx, gy))
        return (gx / norm, gy / norm) if norm > 1e-9 else (0.0, 0.0)

    @property
    def lethal(self) -> BoolGrid:
        if self._dirty:
            self._update()
        return self._lethal

    @property
    def cost(self) -> FloatGrid:
        if self._dirty:
            self._update()
        return self._cost

    def mark_scan(self, scan: LaserScan, pose: Pose2D, max_range: float = 4.0) -> int:
        """Mark lidar hits not already in the map; returns how many new cells were marked.

        Hits within ``hit_tolerance`` of a mapped obstacle are not marked: range noise
        scatters the returns of walls in front of them, and marking those would narrow
        doorways until the planner finds them shut.
        """
        if self._dirty:
            self._update()
        ranges = scan.ranges
        ok = np.isfinite(ranges) & (ranges < max_range) & (ranges > scan.range_min)
        if not ok.any():
            return 0
        ang = scan.angles()[ok] + pose.theta
        xs = pose.x + ranges[ok] * np.cos(ang)
        ys = pose.y + ranges[ok] * np.sin(ang)
        rows = np.floor((ys - self.frame.origin_y) / self.frame.resolution).astype(int)
        cols = np.floor((xs - self.frame.origin_x) / self.frame.resolution).astype(int)
        inside = (rows >= 0) & (rows < self.frame.height) & (cols >= 0) & (cols < self.frame.width)
        # several beams often end in one cell: count (and mark) each cell once
        cells = np.unique(rows[inside] * self.frame.width + cols[inside])
        rows, cols = np.divmod(cells, self.frame.width)
        new = ~self.observed[rows, cols] & (self._static_clearance[rows, cols] > self.hit_tolerance)
        if not new.any():
            return 0
        self.observed[rows[new], cols[new]] = True
        self._dirty = True
        return int(new.sum())

    def clear_observed(self) -> None:
        self.observed[:] = False
        self._dirty = True
