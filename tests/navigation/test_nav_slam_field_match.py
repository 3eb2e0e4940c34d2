"""Sub-cell refinement on the likelihood field: it finds a pose between cells, and along a
corridor, where the scan says nothing, it keeps the odometry's position."""

from __future__ import annotations

import math

import numpy as np

from amiro.core.messages import Pose2D
from amiro.navigation.field_match import DEGENERATE_RATIO, LikelihoodField
from amiro.navigation.occupancy import LogOddsGrid

ANGLES = np.linspace(-math.pi, math.pi, 720, endpoint=False)


def _ranges(pose: Pose2D, walls: list[tuple[str, float]]) -> np.ndarray:
    """Ranges from ``pose`` to axis-aligned walls ('x', c): the line x = c, or ('y', c)."""
    dirs = pose.theta + ANGLES
    dx, dy = np.cos(dirs), np.sin(dirs)
    best = np.full(ANGLES.size, np.inf)
    for axis, c in walls:
        d, start = (dx, pose.x) if axis == "x" else (dy, pose.y)
        with np.errstate(divide="ignore"):
            t = (c - start) / d
        best = np.where((t > 0) & (t < best), t, best)
    return best


def _points(pose: Pose2D, walls: list[tuple[str, float]], max_range: float):
    r = _ranges(pose, walls)
    ok = r < max_range
    return r[ok] * np.cos(ANGLES[ok]), r[ok] * np.sin(ANGLES[ok])


def _mapped(walls: list[tuple[str, float]], views: list[Pose2D], max_range: float) -> LogOddsGrid:
    grid = LogOddsGrid(24.0, 24.0, 0.05, (-12.0, -12.0))
    for view in views:
        px, py = _points(view, walls, max_range)
        c, s = math.cos(view.theta), math.sin(view.theta)
        for _ in range(3):
            grid.integrate(view.x, view.y, view.x + c * px - s * py, view.y + s * px + c * py)
    return grid


def test_refinement_finds_a_pose_between_cells() -> None:
    # walls through cell centres, where a wall of hits is drawn without a half-cell bias
    room = [("x", -2.975), ("x", 3.025), ("y", -2.475), ("y", 2.525)]
    grid = _mapped(room, [Pose2D(0.0, 0.0, 0.0)], 10.0)
    truth = Pose2D(0.137, -0.062, 0.021)
    px, py = _points(truth, room, 10.0)
    start = Pose2D(0.09, -0.02, 0.0)
    field = LikelihoodField.around_scan(grid, px, py, start, 0.5)
    found = field.refine(px, py, start, None, (1.0, 1.0)).pose
    assert start.distance_to(truth) > 0.06
    assert found.distance_to(truth) < 0.015
    assert abs(found.theta - truth.theta) < math.radians(0.3)


def test_along_a_corridor_the_odometry_holds_the_position() -> None:
    corridor = [("y", -0.975), ("y", 1.025)]  # open at both ends, beyond the lidar's reach
    grid = _mapped(corridor, [Pose2D(x, 0.0, 0.0) for x in (-2.0, 0.0, 2.0)], 6.0)
    truth = Pose2D(0.5, 0.08, 0.0)
    px, py = _points(truth, corridor, 6.0)
    odometry = Pose2D(0.8, 0.0, 0.0)  # 30 cm ahead along the corridor, 8 cm across
    start = Pose2D(0.5, 0.0, 0.0)  # where a correlative search left it
    field = LikelihoodField.around_scan(grid, px, py, start, 0.5)
    match = field.refine(px, py, start, odometry, (0.1, 0.05))
    assert abs(match.pose.y - truth.y) < 0.01  # across: the walls decide
    assert abs(match.pose.x - odometry.x) < 0.03  # along: the odometry does
    info = match.information
    assert info[0, 0] < DEGENERATE_RATIO * info[1, 1]  # the scan knows it is blind along x
