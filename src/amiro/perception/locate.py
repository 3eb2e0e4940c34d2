"""People in the map frame from one RGB-D frame: detector boxes + the depth image + where
the robot and its head were.  The improved estimator's whole path on real data."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from amiro.core.messages import BoundingBox2D
from amiro.perception.depth import torso_depth
from amiro.perception.estimation import (
    CameraGeometry,
    FloatArray,
    Views,
    body_centre_row,
    improved,
)

# The visible surface lies this far in front of the body's centre, on average (m).
SURFACE_TO_CENTRE_M = 0.12


def locate_people(
    geom: CameraGeometry,
    depth: FloatArray,
    boxes: Sequence[BoundingBox2D],
    views: Views,
    depth_sigma: float = 1.4e-3,
) -> FloatArray:
    """Body centres (N, 3) in the map frame, one row per box (``views`` has one row per box);
    a row is NaN where the box holds no valid depth.  ``depth`` is the z-depth image in
    metres (0 = no reading), at any resolution with the RGB image's field of view."""
    scale = depth.shape[1] / geom.width
    torso = np.full((len(boxes), 4), np.nan)  # z-depth, column, box top, box bottom
    for i, box in enumerate(boxes):
        found = torso_depth(depth, box, scale, depth_sigma)
        if found is not None:
            torso[i] = *found, box.cy - box.height / 2, box.cy + box.height / 2
    z_depth, u, top, bottom = torso.T
    row = body_centre_row(geom, top, bottom, z_depth, views.head_pitch)
    return improved(geom, u, row, z_depth, views, SURFACE_TO_CENTRE_M)
