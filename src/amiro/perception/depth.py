"""Robust depth of a person from the depth image: the torso region of the box, outliers out.

A box around a person also holds floor, wall and furniture pixels, and depth sensors drop
pixels (zeros) and blur edges.  The person is the densest depth cluster in the torso region,
so the estimate is the median of the fullest window of the sorted depths.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from amiro.core.messages import BoundingBox2D

FloatArray = npt.NDArray[np.float64]

# The torso region as fractions of the box: central columns and rows around the centre.
TORSO_COLUMNS = (0.3, 0.7)
TORSO_ROWS = (0.3, 0.7)


def region(
    depth: FloatArray,
    box: BoundingBox2D,
    scale: float,
    cols: tuple[float, float],
    rows: tuple[float, float],
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Depth pixels of a sub-rectangle of ``box`` (RGB pixels; ``scale`` = depth/RGB width)
    with their depth-image coordinates (column, row) as RGB-image pixels."""
    h, w = depth.shape
    u0, v0 = box.cx - box.width / 2.0, box.cy - box.height / 2.0
    c0 = int(np.floor((u0 + cols[0] * box.width) * scale))
    c1 = int(np.ceil((u0 + cols[1] * box.width) * scale))
    r0 = int(np.floor((v0 + rows[0] * box.height) * scale))
    r1 = int(np.ceil((v0 + rows[1] * box.height) * scale))
    c0, r0 = max(c0, 0), max(r0, 0)
    c1, r1 = min(max(c1, c0 + 1), w), min(max(r1, r0 + 1), h)
    patch = depth[r0:r1, c0:c1]
    rr, cc = np.mgrid[r0:r1, c0:c1]
    return patch.ravel(), (cc.ravel() + 0.5) / scale, (rr.ravel() + 0.5) / scale


def densest_cluster(values: FloatArray, width: float) -> npt.NDArray[np.bool_]:
    """Mask of the values in the fullest window of ``width`` (positive values only)."""
    valid = np.isfinite(values) & (values > 0)
    if not valid.any():
        return valid
    ordered = np.sort(values[valid])
    ends = np.searchsorted(ordered, ordered + width, side="right")
    start = int(np.argmax(ends - np.arange(len(ordered))))
    lo, hi = ordered[start], ordered[start] + width
    inside: npt.NDArray[np.bool_] = valid & (values >= lo) & (values <= hi)
    return inside


def torso_depth(
    depth: FloatArray, box: BoundingBox2D, scale: float, sigma_per_m2: float = 1.4e-3
) -> tuple[float, float] | None:
    """(z-depth, u) of the torso: the median inlier depth and the median inlier column (in
    RGB pixels; robust to a box clipped by the image border); None when the region holds
    no valid depth."""
    values, us, _ = region(depth, box, scale, TORSO_COLUMNS, TORSO_ROWS)
    rough = float(np.median(values[values > 0])) if (values > 0).any() else 0.0
    if rough <= 0:
        return None
    inliers = densest_cluster(values, max(0.15, 6.0 * sigma_per_m2 * rough * rough))
    return float(np.median(values[inliers])), float(np.median(us[inliers]))


def centre_depth(depth: FloatArray, box: BoundingBox2D, scale: float) -> float:
    """The depth reading at the box centre (median of the valid 3x3 pixels; 0 if none):
    the paper's ``d``."""
    h, w = depth.shape
    c = min(max(int(box.cx * scale), 0), w - 1)
    r = min(max(int(box.cy * scale), 0), h - 1)
    patch = depth[max(r - 1, 0) : r + 2, max(c - 1, 0) : c + 2]
    valid = patch[patch > 0]
    return float(np.median(valid)) if valid.size else 0.0
