"""Planar pose algebra (SE(2)) shared by odometry handling, localisation and SLAM."""

from __future__ import annotations

import math

from amiro.core.geometry import wrap_angle
from amiro.core.messages import Pose2D


def compose(a: Pose2D, b: Pose2D) -> Pose2D:
    """``a ⊕ b``: pose ``b`` (expressed in ``a``'s frame) in ``a``'s parent frame."""
    c, s = math.cos(a.theta), math.sin(a.theta)
    return Pose2D(a.x + c * b.x - s * b.y, a.y + s * b.x + c * b.y, wrap_angle(a.theta + b.theta))


def between(a: Pose2D, b: Pose2D) -> Pose2D:
    """The pose of ``b`` seen from ``a``, so that ``compose(a, between(a, b)) == b``."""
    dx, dy = b.x - a.x, b.y - a.y
    c, s = math.cos(a.theta), math.sin(a.theta)
    return Pose2D(c * dx + s * dy, -s * dx + c * dy, wrap_angle(b.theta - a.theta))
