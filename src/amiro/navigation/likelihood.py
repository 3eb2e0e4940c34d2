"""The likelihood-field sensor model: how well a lidar endpoint fits a known map.

Precomputed once per map with a Euclidean distance transform, so scoring thousands of
hypotheses is a table look-up per beam endpoint (Thrun et al., *Probabilistic Robotics* 6.4).
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt
from scipy import ndimage

from amiro.core.gridmap import FREE, GridMap

FloatArray = npt.NDArray[np.float64]


class LikelihoodField:
    """Log-likelihood of an endpoint per cell: a Gaussian on the distance to the nearest
    obstacle mixed with a uniform floor for unexplained returns; off-map reads the floor."""

    def __init__(self, grid: GridMap, sigma: float = 0.1, z_hit: float = 0.9) -> None:
        self.grid = grid
        occupied = grid.data > 50
        dist = ndimage.distance_transform_edt(~occupied) * grid.resolution
        floor = (1.0 - z_hit) * 0.05  # a random return, per 0.05 m of range
        p = z_hit * np.exp(-0.5 * (dist / sigma) ** 2) + floor
        p[grid.data < 0] = floor  # unknown cells explain nothing
        self.floor = float(np.log(floor))
        self.log_p = np.log(p).astype(np.float32)
        self.free = grid.data == FREE
        # what a beam ending one cell from a wall scores: the fit of a scan that matches
        self.matched_p = float(z_hit * np.exp(-0.5 * (grid.resolution / sigma) ** 2) + floor)

    def log_likelihoods(self, xs: FloatArray, ys: FloatArray) -> FloatArray:
        """Log-likelihood of every endpoint (float32, shaped like ``xs``)."""
        col, row = self.grid.world_to_cell(xs, ys)
        inside = self.grid.in_bounds(col, row)
        h, w = self.log_p.shape
        flat = np.clip(row, 0, h - 1) * w + np.clip(col, 0, w - 1)
        return np.where(inside, self.log_p.reshape(-1)[flat], np.float32(self.floor))

    def score(self, xs: FloatArray, ys: FloatArray) -> FloatArray:
        """Summed log-likelihood over the last axis of endpoint arrays shaped (..., beams)."""
        return np.asarray(self.log_likelihoods(xs, ys).sum(axis=-1), dtype=np.float64)
