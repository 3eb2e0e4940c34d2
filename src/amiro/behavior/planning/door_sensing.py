"""Is a door open or closed?  Asked of one lidar scan, never of the simulator.

Each beam that crosses the door's opening is compared with the distance to the door line:
ending at the line means the panel is there, going on well beyond means the way is open, and
ending well before means something else hides the door (that beam says nothing).  A beam is
used only if it passes the whole thickness of the wall inside the opening: at a grazing angle
a beam that crosses the line in the opening can end on the wall's face beside the door or on
the jamb beyond it, as near the line as a closed panel would be.
"""

from __future__ import annotations

import math

import numpy as np

from amiro.behavior.planning.knowledge import DoorState
from amiro.core.messages import LaserScan, Pose2D

FRAME_MARGIN_M = 0.1  # beams this close to the door frame are not used
WALL_HALF_THICKNESS_M = 0.1  # each side of the door line: walls up to 0.2 m thick
THROUGH_M = 0.3  # a beam this far beyond the door line went through the opening
MIN_BEAMS = 3
AGREEMENT = 0.7


def door_state_from_scan(
    scan: LaserScan,
    pose: Pose2D,
    a: tuple[float, float],
    b: tuple[float, float],
    max_range_m: float = 6.0,
) -> DoorState | None:
    """OPEN or CLOSED when enough beams agree; None when the door is out of view."""
    ax, ay = a
    bx, by = b
    length = math.hypot(bx - ax, by - ay)
    if length <= 2 * FRAME_MARGIN_M:
        return None
    ux, uy = (bx - ax) / length, (by - ay) / length
    angles = scan.angles() + pose.theta
    dx, dy = np.cos(angles), np.sin(angles)
    # ray (pose + t d) against segment (a + s u): solve with 2-D cross products
    denom = dx * uy - dy * ux
    with np.errstate(divide="ignore", invalid="ignore"):
        wx, wy = ax - pose.x, ay - pose.y
        t = (wx * uy - wy * ux) / denom
        s = (wx * dy - wy * dx) / denom
    # along the door, how far the beam drifts while it crosses the wall's half thickness
    drift = WALL_HALF_THICKNESS_M * np.abs(dx * ux + dy * uy) / np.maximum(np.abs(denom), 1e-9)
    margin = FRAME_MARGIN_M + drift
    crossing = (
        (np.abs(denom) > 1e-9)
        & (t > 0.0)
        & (t < max_range_m)
        & (s > margin)
        & (s < length - margin)
    )
    if int(crossing.sum()) < MIN_BEAMS:
        return None
    ranges = np.where(np.isfinite(scan.ranges), scan.ranges, np.inf)[crossing]
    expected = t[crossing]
    # a thin panel seen at a grazing angle ends the beam further along it
    tolerance = 0.1 + 0.05 / np.maximum(np.abs(denom[crossing]), 0.2)
    closed = np.abs(ranges - expected) <= tolerance
    through = ranges > expected + np.maximum(tolerance, THROUGH_M)
    informative = int(closed.sum() + through.sum())
    if informative < MIN_BEAMS:
        return None
    if closed.sum() >= AGREEMENT * informative:
        return DoorState.CLOSED
    if through.sum() >= AGREEMENT * informative:
        return DoorState.OPEN
    return None
