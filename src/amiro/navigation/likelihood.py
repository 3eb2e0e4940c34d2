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
    obstacle mixed with a uniform floor for unexplained returns; off-map reads the floor.

    Some maps draw the building's boundaries as unknown rather than occupied (the free
    space simply ends): there the edge of the free space is the obstacle, and the Gaussian
    reaches into the unknown beyond it, where the walls really are."""

    def __init__(self, grid: GridMap, sigma: float = 0.1, z_hit: float = 0.9) -> None:
        self.grid = grid
        occupied = grid.data > 50
        unknown = grid.data < 0
        edge = unknown_boundary(grid)
        if edge is not None:
            occupied |= edge
        dist = ndimage.distance_transform_edt(~occupied) * grid.resolution
        floor = (1.0 - z_hit) * 0.05  # a random return, per 0.05 m of range
        p = z_hit * np.exp(-0.5 * (dist / sigma) ** 2) + floor
        if edge is not None:
            unknown &= dist > 3.0 * sigma
        p[unknown] = floor  # unknown cells explain nothing
        self.boundaries_unknown = edge is not None
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


def unknown_boundary(grid: GridMap) -> npt.NDArray[np.bool_] | None:
    """The unknown cells bordering free space, when most of the free space's border is
    unknown rather than occupied (a map that leaves its walls out); else None."""
    free = grid.data == FREE
    unknown = grid.data < 0
    occupied = grid.data > 50
    ring = np.ones((3, 3), dtype=bool)
    border = free & ~ndimage.binary_erosion(free, ring, border_value=1)
    near_occupied = ndimage.binary_dilation(occupied, ring)
    open_border = border & ~near_occupied
    if open_border.sum() <= (border & near_occupied).sum():
        return None
    return np.asarray(unknown & ndimage.binary_dilation(free, ring))
