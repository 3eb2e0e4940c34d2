"""PathFollower driven in closed loop with an ideal omnidirectional base."""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import pytest

from amiro.core.geometry import wrap_angle as wrap
from amiro.core.messages import Pose2D
from amiro.navigation.follower import FollowerLimits, PathFollower

DT = 0.1  # the navigation control period (10 Hz)


@dataclass
class Run:
    poses: list[Pose2D] = field(default_factory=list)
    speeds: list[float] = field(default_factory=list)
    turns: list[float] = field(default_factory=list)
    arrived: bool = False
    time: float = 0.0


def _drive(follower: PathFollower, start: Pose2D, max_time: float = 60.0) -> Run:
    """Integrate the commanded body twist exactly-enough (10 sub-steps per cycle)."""
    run = Run(poses=[start])
    pose = start
    while run.time < max_time:
        twist, arrived = follower.command(pose)
        if arrived:
            run.arrived = True
            break
        vx, vy, wz = twist.linear.x, twist.linear.y, twist.angular.z
        run.speeds.append(math.hypot(vx, vy))
        run.turns.append(abs(wz))
        x, y, th = pose.x, pose.y, pose.theta
        for _ in range(10):
            h = DT / 10
            c, s = math.cos(th), math.sin(th)
            x += (c * vx - s * vy) * h
            y += (s * vx + c * vy) * h
            th += wz * h
        pose = Pose2D(x, y, wrap(th))
        run.poses.append(pose)
        run.time += DT
    return run


def _distance_to_path(p: Pose2D, path: list[Pose2D]) -> float:
    best = math.inf
    for a, b in itertools.pairwise(path):
        dx, dy = b.x - a.x, b.y - a.y
        t = ((p.x - a.x) * dx + (p.y - a.y) * dy) / (dx * dx + dy * dy)
        t = min(1.0, max(0.0, t))
        best = min(best, math.hypot(a.x + t * dx - p.x, a.y + t * dy - p.y))
    return best


L_PATH = [Pose2D(0.0, 0.0, 0.0), Pose2D(3.0, 0.0, math.pi / 2), Pose2D(3.0, 2.0, math.pi)]


@pytest.mark.parametrize(
    "start",
    [
        Pose2D(0.0, 0.0, 0.0),  # on the path, facing along it
        Pose2D(0.0, 0.0, math.pi / 2),  # facing sideways: turns while it goes
        Pose2D(0.05, -0.05, -2.5),  # a little off the path, facing backwards
    ],
)
def test_follows_an_l_shaped_path_to_the_goal_pose(start: Pose2D) -> None:
    limits = FollowerLimits()
    follower = PathFollower(limits)
    follower.set_path(list(L_PATH))
    run = _drive(follower, start)
    goal = L_PATH[-1]
    assert run.arrived, f"not arrived after {run.time:.1f} s at {run.poses[-1]}"
    end = run.poses[-1]
    assert end.distance_to(goal) <= limits.goal_tolerance + 1e-9
    assert abs(wrap(end.theta - goal.theta)) <= limits.heading_tolerance + 1e-9
    worst = max(_distance_to_path(p, L_PATH) for p in run.poses)
    assert worst <= 0.15, f"deviates {worst:.3f} m from the path"
    assert max(run.speeds) <= limits.max_speed + 1e-9
    assert max(run.turns) <= limits.max_turn + 1e-9
    # 5 m at up to 0.35 m/s: no dawdling (slow-down near the goal and turning included)
    assert 5.0 / limits.max_speed <= run.time + 0.1 < 30.0


def test_corner_cut_is_small_compared_with_the_lookahead() -> None:
    limits = FollowerLimits(lookahead=0.35)
    follower = PathFollower(limits)
    follower.set_path(list(L_PATH))
    run = _drive(follower, Pose2D(0.0, 0.0, 0.0))
    assert run.arrived
    corner = min(math.hypot(p.x - 3.0, p.y) for p in run.poses)
    assert corner < limits.lookahead / 2, f"passes {corner:.2f} m from the corner"
    # it does turn the corner: no pose beyond the far end of the first leg
    assert max(p.x for p in run.poses) <= 3.0 + 0.05


def test_faces_the_travel_direction_mid_segment() -> None:
    follower = PathFollower()
    follower.set_path([Pose2D(0.0, 0.0, 0.0), Pose2D(4.0, 0.0, 0.0)])
    run = _drive(follower, Pose2D(0.0, 0.0, math.pi / 2))
    assert run.arrived
    mid = [p for p in run.poses if 1.5 < p.x < 2.5]
    assert mid and all(abs(wrap(p.theta)) < 0.1 for p in mid)


def test_slows_down_near_the_goal_and_remaining_shrinks() -> None:
    limits = FollowerLimits()
    follower = PathFollower(limits)
    follower.set_path(list(L_PATH))
    pose = Pose2D(0.0, 0.0, 0.0)
    assert follower.remaining(pose) == pytest.approx(5.0)
    run = _drive(follower, pose)
    assert run.arrived
    rem = [follower.remaining(p) for p in run.poses[-5:]]
    assert rem[-1] <= limits.goal_tolerance + 1e-9
    fast = [s for s, p in zip(run.speeds, run.poses, strict=False) if 0.5 < p.x < 2.0]
    assert fast and min(fast) > 0.9 * limits.max_speed
    assert run.speeds[-1] < 0.3 * limits.max_speed


def test_single_pose_path_and_empty_path() -> None:
    follower = PathFollower()
    twist, arrived = follower.command(Pose2D())
    assert arrived and twist.linear.x == 0.0 and twist.angular.z == 0.0
    follower.set_path([Pose2D(0.5, 0.3, 1.0)])
    run = _drive(follower, Pose2D(0.0, 0.0, 0.0))
    assert run.arrived
    assert run.poses[-1].distance_to(Pose2D(0.5, 0.3)) <= 0.08 + 1e-9
    assert abs(wrap(run.poses[-1].theta - 1.0)) <= 0.08 + 1e-9


def test_already_at_the_goal_only_turns() -> None:
    follower = PathFollower()
    follower.set_path([Pose2D(0.0, 0.0, 0.0), Pose2D(1.0, 0.0, math.pi / 2)])
    twist, arrived = follower.command(Pose2D(1.0, 0.02, 0.0))
    assert not arrived
    assert twist.linear.x == 0.0 and twist.linear.y == 0.0
    assert twist.angular.z > 0.5
