"""Trajectory metrics: absolute trajectory error after alignment, and dynamic time warping."""

from __future__ import annotations

import itertools
import math

import numpy as np
import numpy.typing as npt

from amiro.core.messages import Pose2D

FloatArray = npt.NDArray[np.float64]


def ate_rmse(estimate: FloatArray, reference: FloatArray) -> float:
    """RMSE (m) of positions (n, 2) after the rigid 2D alignment that best fits the reference
    (Umeyama without scale), so a different map origin is not counted as error."""
    return _aligned_rmse(estimate, reference, with_scale=False)[0]


def ate_similarity(estimate: FloatArray, reference: FloatArray) -> tuple[float, float]:
    """RMSE (m) after the best similarity alignment, and that alignment's scale: separates
    a map that is uniformly too small or large (scale != 1, invisible to loop closure) from
    one that is bent or torn (the RMSE left after scaling)."""
    return _aligned_rmse(estimate, reference, with_scale=True)


def align(estimate: FloatArray, reference: FloatArray) -> FloatArray:
    """``estimate`` moved by the rigid 2D transform that best fits it onto ``reference``."""
    return _umeyama(estimate, reference, with_scale=False)[0]


def _aligned_rmse(
    estimate: FloatArray, reference: FloatArray, with_scale: bool
) -> tuple[float, float]:
    aligned, scale = _umeyama(estimate, reference, with_scale)
    return float(np.sqrt(np.mean(np.sum((aligned - reference) ** 2, axis=1)))), scale


def _umeyama(
    estimate: FloatArray, reference: FloatArray, with_scale: bool
) -> tuple[FloatArray, float]:
    """Umeyama (1991): the rotation (and scale) mapping ``estimate`` onto ``reference``."""
    mu_e, mu_r = estimate.mean(axis=0), reference.mean(axis=0)
    e, r = estimate - mu_e, reference - mu_r
    u, sv, vt = np.linalg.svd(e.T @ r)
    flip = np.diag([1.0, np.sign(np.linalg.det(u @ vt))])
    rot = (u @ flip @ vt).T
    scale = float(np.sum(sv * np.diag(flip)) / np.sum(e**2)) if with_scale else 1.0
    return scale * e @ rot.T + mu_r, scale


def resample(points: list[Pose2D], spacing: float = 0.1) -> FloatArray:
    """Points every ``spacing`` metres along a polyline (ends included)."""
    xy = np.array([[p.x, p.y] for p in points], dtype=np.float64)
    if len(xy) < 2:
        return xy
    seg = np.hypot(*np.diff(xy, axis=0).T)
    s = np.concatenate(([0.0], np.cumsum(seg)))
    if s[-1] <= 0.0:
        return xy[:1]
    t = np.append(np.arange(0.0, s[-1], spacing), s[-1])
    return np.column_stack((np.interp(t, s, xy[:, 0]), np.interp(t, s, xy[:, 1])))


def dtw(a: FloatArray, b: FloatArray) -> float:
    """Dynamic time warping distance: the smallest sum of point distances over a monotone
    alignment of the two sequences (both resampled at the same spacing by the caller)."""
    cost = np.hypot(a[:, None, 0] - b[None, :, 0], a[:, None, 1] - b[None, :, 1])
    acc = np.full((len(a) + 1, len(b) + 1), np.inf)
    acc[0, 0] = 0.0
    for i in range(1, len(a) + 1):
        row = acc[i]
        prev = acc[i - 1]
        diag_up = np.minimum(prev[:-1], prev[1:]) + cost[i - 1]
        # the left dependency is sequential: a running minimum along the row
        for j in range(1, len(b) + 1):
            row[j] = min(diag_up[j - 1], row[j - 1] + cost[i - 1, j - 1])
    return float(acc[-1, -1])


def path_length(points: list[Pose2D]) -> float:
    return sum(math.hypot(b.x - a.x, b.y - a.y) for a, b in itertools.pairwise(points))
