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
    out = np.zeros((n_theta, n_off, n_off))
    mass = np.zeros((n_off, n_off))
    # point by point, a row of the grid at a time: the column offsets read contiguous cells
    for k in range(n_theta):
        mass[:, :] = 0.0
        for i in range(n_pts):
            for a in range(n_off):
                r = rows[k, i] + offsets[a]
                if r < 0 or r >= h:
                    continue
                for b in range(n_off):
                    c = cols[k, i] + offsets[b]
                    if 0 <= c < w:
                        out[k, a, b] += hit[r, c]
                        mass[a, b] += known[r, c]
        for a in range(n_off):
            for b in range(n_off):
                out[k, a, b] /= max(mass[a, b], min_known)
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


@numba.njit(cache=True)
def mean_lattice(
    grid: Grid, rows: IntArray, cols: IntArray, offsets: IntArray
) -> FloatArray:  # pragma: no cover - compiled
    """``out[k, a, b]``: the mean of ``grid`` over the points' cells (as ``score_lattice``,
    every point counted; outside the grid reads 0)."""
    h, w = grid.shape
    n_theta, n_pts = rows.shape
    n_off = offsets.size
    out = np.zeros((n_theta, n_off, n_off))
    for k in range(n_theta):
        for i in range(n_pts):
            for a in range(n_off):
                r = rows[k, i] + offsets[a]
                if r < 0 or r >= h:
                    continue
                for b in range(n_off):
                    c = cols[k, i] + offsets[b]
                    if 0 <= c < w:
                        out[k, a, b] += grid[r, c]
    out /= max(n_pts, 1)
    return out


@numba.njit(cache=True)
def integrate_beams(
    logodds: Grid,
    mark: npt.NDArray[np.uint8],
    x: float,
    y: float,
    hx: FloatArray,
    hy: FloatArray,
    origin_x: float,
    origin_y: float,
    resolution: float,
    free_margin: float,
    l_free: float,
    l_occ: float,
    clamp: float,
    changed: npt.NDArray[np.int64],
) -> int:  # pragma: no cover - compiled
    """One scan's log-odds update (see ``LogOddsGrid.integrate``): each cell a beam crosses
    short of its hit is lowered once, each hit cell raised once (a cell both crossed and hit
    takes only the hit).  Writes the flat indices of the changed cells into ``changed`` and
    returns their count; ``mark`` must be all zero and is left so."""
    h, w = logodds.shape
    flat = logodds.reshape(-1)
    flat_mark = mark.reshape(-1)
    n_beams = hx.size
    count = 0
    longest = 0.0
    for i in range(n_beams):
        length = np.hypot(hx[i] - x, hy[i] - y)
        longest = max(longest, length)
        col = int(np.floor((hx[i] - origin_x) / resolution))
        row = int(np.floor((hy[i] - origin_y) / resolution))
        if 0 <= col < w and 0 <= row < h:
            cell = row * w + col
            if flat_mark[cell] != 2:
                if flat_mark[cell] == 0:
                    changed[count] = cell
                    count += 1
                flat_mark[cell] = 2
    n = int(np.ceil(longest / resolution))
    for i in range(n_beams):
        length = np.hypot(hx[i] - x, hy[i] - y)
        short = max(resolution, free_margin * length)
        for k in range(n):
            t = (k + 0.5) / n
            if t * length >= length - short:
                break
            col = int(np.floor((x + t * (hx[i] - x) - origin_x) / resolution))
            row = int(np.floor((y + t * (hy[i] - y) - origin_y) / resolution))
            if 0 <= col < w and 0 <= row < h:
                cell = row * w + col
                if flat_mark[cell] == 0:
                    flat_mark[cell] = 1
                    changed[count] = cell
                    count += 1
    lf = np.float32(l_free)
    lo = np.float32(l_occ)
    cl = np.float32(clamp)
    for j in range(count):
        cell = changed[j]
        if flat_mark[cell] == 2:
            flat[cell] = min(flat[cell] + lo, cl)
        else:
            flat[cell] = max(flat[cell] + lf, -cl)
        flat_mark[cell] = 0
    return count
