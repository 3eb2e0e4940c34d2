"""GlobalPlanner on a synthetic room and on the shipped apartment map."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from amiro.core.gridmap import load_map
from amiro.core.messages import Point, Pose2D
from amiro.home.world import World, default_home_path
from amiro.navigation.config import NavigationConfig
from amiro.navigation.costmap import Costmap, GridFrame
from amiro.navigation.planner import GlobalPlanner
from amiro.navigation.stack import costmap_from_map

RES = 0.1


def _room() -> Costmap:
    """A 6 m x 4 m room (walls one cell thick) split by a wall at x = 3 with a 1 m gap."""
    h, w = 40, 60
    static = np.zeros((h, w), dtype=bool)
    static[0, :] = static[-1, :] = static[:, 0] = static[:, -1] = True
    static[:, 30] = True
    static[5:15, 30] = False  # gap at y in [0.5, 1.5)
    return Costmap(static, GridFrame(RES, 0.0, 0.0, h, w), robot_radius=0.25, safety_margin=0.08)


def _lethal_at(cm: Costmap, x: float, y: float) -> bool:
    r, c = cm.frame.to_cell(x, y)
    return not cm.frame.inside(r, c) or bool(cm.lethal[r, c])


def _assert_collision_free(cm: Costmap, path: list[Pose2D], step: float = 0.01) -> None:
    for a, b in itertools.pairwise(path):
        n = max(1, int(math.hypot(b.x - a.x, b.y - a.y) / step))
        for i in range(n + 1):
            t = i / n
            x, y = a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)
            assert not _lethal_at(cm, x, y), f"path crosses a lethal cell at ({x:.2f}, {y:.2f})"


def _length(path: list[Pose2D]) -> float:
    return sum(a.distance_to(b) for a, b in itertools.pairwise(path))


def test_plan_to_pose_ends_exactly_at_the_goal_and_stays_free() -> None:
    cm = _room()
    planner = GlobalPlanner(cm)
    start, goal = Pose2D(1.0, 3.0, 0.3), Pose2D(5.0, 3.0, -2.0)
    path = planner.plan_to_pose(start, goal)
    assert path is not None
    assert path[-1] == goal  # position and heading exactly
    assert path[0].distance_to(start) < RES
    _assert_collision_free(cm, path)
    # it must pass through the gap (y in [0.5, 1.5)) at x = 3
    crossing = [
        a.y + (3.05 - a.x) / (b.x - a.x) * (b.y - a.y)
        for a, b in itertools.pairwise(path)
        if min(a.x, b.x) <= 3.05 <= max(a.x, b.x) and b.x != a.x
    ]
    assert crossing and all(0.5 <= y < 1.5 for y in crossing)
    # intermediate poses face the next waypoint
    for a, b in itertools.pairwise(path[:-1]):
        assert a.theta == pytest.approx(math.atan2(b.y - a.y, b.x - a.x))
    # pruned: a handful of waypoints, not one per cell, and not much longer than needed
    assert len(path) <= 8
    lower = math.hypot(3.05 - 1.0, 1.45 - 3.0) + math.hypot(5.0 - 3.05, 3.0 - 1.45)
    assert lower <= _length(path) < 1.25 * lower


def test_plan_to_pose_unreachable_or_outside_is_none() -> None:
    cm = _room()
    cm.static[5:15, 30] = True  # close the gap
    cm._dirty = True
    planner = GlobalPlanner(cm)
    assert planner.plan_to_pose(Pose2D(1.0, 3.0), Pose2D(5.0, 3.0)) is None
    assert planner.plan_to_pose(Pose2D(1.0, 3.0), Pose2D(50.0, 3.0)) is None
    assert planner.plan_to_pose(Pose2D(-3.0, 3.0), Pose2D(2.0, 2.0)) is None
    # the goal itself inside an inflated wall
    assert planner.plan_to_pose(Pose2D(1.0, 3.0), Pose2D(2.0, 0.15)) is None


def test_start_inside_the_inflation_zone_still_plans() -> None:
    cm = _room()
    planner = GlobalPlanner(cm)
    start = Pose2D(0.35, 2.0, 0.0)  # 0.3 m from the wall: inside the lethal zone
    assert _lethal_at(cm, start.x, start.y)
    path = planner.plan_to_pose(start, Pose2D(2.0, 2.0))
    assert path is not None and path[-1] == Pose2D(2.0, 2.0)
    assert path[0].distance_to(start) <= 0.3 + RES
    _assert_collision_free(cm, path)


@pytest.mark.parametrize(
    ("target", "approach"),
    [(Point(4.55, 3.05), 1.0), (Point(1.55, 1.55), 0.8), (Point(5.65, 0.35), 1.2)],
)
def test_plan_near_stops_at_the_approach_distance_facing_the_target(
    target: Point, approach: float
) -> None:
    cm = _room()
    planner = GlobalPlanner(cm)
    tol = 0.2
    path = planner.plan_near(Pose2D(1.0, 3.0, 0.0), target, approach, tolerance=tol)
    assert path is not None
    end = path[-1]
    assert abs(end.distance_to(target) - approach) <= tol + 1e-9
    assert end.theta == pytest.approx(math.atan2(target.y - end.y, target.x - end.x))
    assert not _lethal_at(cm, end.x, end.y)
    _assert_collision_free(cm, path)


def test_plan_near_a_target_with_no_free_ring_is_none() -> None:
    cm = _room()
    cm.static[5:15, 30] = True
    cm._dirty = True
    planner = GlobalPlanner(cm)
    # every spot 0.5 m (± 0.1) from the target lies beyond the closed wall
    assert planner.plan_near(Pose2D(1.0, 3.0), Point(4.5, 2.0), 0.5, tolerance=0.1) is None


def test_shipped_map_plans_between_all_places() -> None:
    grid = load_map(default_home_path().with_name("map.yaml"))
    world = World.load(default_home_path())
    cm = costmap_from_map(grid, NavigationConfig())
    assert cm.frame.resolution == pytest.approx(0.1)
    planner = GlobalPlanner(cm)
    dock = world.place("dock")
    for name in world.home.places:
        place = world.place(name)
        assert not _lethal_at(cm, place.x, place.y), f"place {name} is lethal in the costmap"
        path = planner.plan_to_pose(dock, place)
        assert path is not None, name
        assert path[-1] == place
        _assert_collision_free(cm, path)
    # a person on the couch, approached at 1.2 m
    seat = world.seat("couch_left")
    path = planner.plan_near(dock, Point(seat.x, seat.y), 1.2)
    assert path is not None
    end = path[-1]
    # the ring is centred on the target's cell: allow half a cell diagonal on top of ± 0.25
    assert abs(end.distance_to(Point(seat.x, seat.y)) - 1.2) <= 0.25 + 0.75 * cm.frame.resolution
    assert not _lethal_at(cm, end.x, end.y)


def test_plan_near_keeps_to_the_requested_distance_when_it_is_free() -> None:
    # open floor around the target: the ring's near edge used to win (asked 1.2, got ~1.45)
    cm = _room()
    planner = GlobalPlanner(cm)
    target = Point(4.53, 2.47)
    for approach in (0.8, 1.0, 1.2):
        path = planner.plan_near(Pose2D(1.0, 3.0, 0.0), target, approach, tolerance=0.25)
        assert path is not None
        assert abs(path[-1].distance_to(target) - approach) <= 0.75 * RES + 1e-9


def test_plan_starts_at_the_robot_not_at_its_cell_centre() -> None:
    cm = _room()
    start = Pose2D(1.03, 3.07, 0.0)
    path = GlobalPlanner(cm).plan_to_pose(start, Pose2D(2.0, 3.0))
    assert path is not None
    assert (path[0].x, path[0].y) == (start.x, start.y)
