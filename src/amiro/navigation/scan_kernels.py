"""Compiled inner loops of scan matching (numba): scoring a lattice of poses on a grid.

An exhaustive correlative search scores every (rotation, row offset, column offset) of a
window; in numpy that needs a points x offsets temporary per rotation (most of the time of
a loop-closure search went into allocating and summing it).  Here it is a plain triple loop.
"""

from __future__ import annotations

import numba
import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]
Grid = npt.NDArray[np.float32]


@numba.njit(cache=True)
def score_lattice(
    hit: Grid,
    known: Grid,
    rows: IntArray,
    cols: IntArray,
    offsets: IntArray,
    min_known: float,
) -> FloatArray:  # pragma: no cover - compiled
    """``out[k, a, b]``: the mean of ``hit`` over the cells of the points rotated by
    rotation k (cells ``rows[k]``, ``cols[k]``) shifted by (offsets[a], offsets[b]), divided by
    the ``known`` mass the points land on (at least ``min_known``); outside reads 0."""
    h, w = hit.shape
    n_theta, n_pts = rows.shape
    n_off = offsets.size
    out = np.empty((n_theta, n_off, n_off))
    for k in range(n_theta):
        for a in range(n_off):
            for b in range(n_off):
                s = 0.0
                kn = 0.0
                for i in range(n_pts):
                    r = rows[k, i] + offsets[a]
                    c = cols[k, i] + offsets[b]
                    if 0 <= r < h and 0 <= c < w:
                        s += hit[r, c]
                        kn += known[r, c]
                out[k, a, b] = s / max(kn, min_known)
    return out


def lattice_cells(
    px: FloatArray,
    py: FloatArray,
    x: float,
    y: float,
    thetas: FloatArray,
    origin: tuple[float, float],
    resolution: float,
) -> tuple[IntArray, IntArray]:
    """The cells (rows, cols; one row per rotation) of points (px, py) seen from (x, y)."""
    c = np.cos(thetas)[:, None]
    s = np.sin(thetas)[:, None]
    wx = x + c * px[None, :] - s * py[None, :]
    wy = y + s * px[None, :] + c * py[None, :]
    cols = np.floor((wx - origin[0]) / resolution).astype(np.int64)
    rows = np.floor((wy - origin[1]) / resolution).astype(np.int64)
    return rows, cols
