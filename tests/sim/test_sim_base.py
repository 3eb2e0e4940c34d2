"""Pepper's omnidirectional base: limits, collisions and odometry drift."""

from __future__ import annotations

import math

import numpy as np

from amiro.core.gridmap import GridMap
from amiro.core.messages import Pose2D
from amiro.home.world import World, default_home_path
from amiro.sim.base import BaseLimits, Odometry, OmniBase

DT = 0.05


def run(base: OmniBase, seconds: float, is_free: object = None) -> list[tuple[float, float, float]]:
    vel = []
    for _ in range(round(seconds / DT)):
        base.step(DT, is_free)  # type: ignore[arg-type]
        vel.append(base.velocity)
    return vel


def test_velocity_and_acceleration_limits() -> None:
    base = OmniBase(Pose2D())
    base.set_command(2.0, 0.0, 5.0)
    assert base.command == (0.35, 0.0, 1.0)
    vel = run(base, 2.0)
    vx = np.array([v[0] for v in vel])
    wz = np.array([v[2] for v in vel])
    assert vx.max() <= 0.35 + 1e-9 and wz.max() <= 1.0 + 1e-9
    assert np.diff(np.concatenate([[0.0], vx])).max() <= 0.5 * DT + 1e-9
    assert np.diff(np.concatenate([[0.0], wz])).max() <= 2.0 * DT + 1e-9
    assert vx[-1] == 0.35  # reaches the limit
    base.set_command(0.3, 0.3, 0.0)  # the limit applies to the norm
    assert math.hypot(*base.command[:2]) <= 0.35 + 1e-9


def test_omnidirectional_and_rotation_in_place() -> None:
    base = OmniBase(Pose2D(0.0, 0.0, math.pi / 2))
    base.set_command(0.0, 0.2, 0.0)  # sideways left = world -x when facing +y
    run(base, 3.0)
    assert base.pose.x < -0.4 and abs(base.pose.y) < 1e-6
    assert abs(base.pose.theta - math.pi / 2) < 1e-9
    base = OmniBase(Pose2D(1.0, 2.0, 0.0))
    base.set_command(0.0, 0.0, 0.5)
    run(base, 2.0)
    assert (base.pose.x, base.pose.y) == (1.0, 2.0)
    assert 0.7 < base.pose.theta < 1.0


def test_driving_into_a_wall_stops_counts_once_and_never_penetrates() -> None:
    world = World.load(default_home_path())
    base = OmniBase(Pose2D(1.5, 1.0, 0.0))  # wall x=3 (0.1 thick) ahead
    base.set_command(0.35, 0.0, 0.0)
    for _ in range(400):
        base.step(DT, world.is_free)
        assert base.pose.x + 0.25 <= 3.0 - 0.05 + 1e-9  # never into the wall's cells
    assert base.collisions == 1
    assert base.velocity == (0.0, 0.0, 0.0)
    assert base.pose.x > 2.5
    base.set_command(0.0, 0.0, 1.0)  # turning in place while touching is allowed
    run(base, 1.0, world.is_free)
    assert base.collisions == 1 and base.pose.theta > 0.5
    base.set_command(-0.3, 0.0, 0.0)  # back off, then hit again: a new contact
    base.pose = Pose2D(base.pose.x, base.pose.y, 0.0)
    run(base, 2.0, world.is_free)
    base.set_command(0.35, 0.0, 0.0)
    run(base, 4.0, world.is_free)
    assert base.collisions == 2


def rotate_once(seed: int) -> float:
    """Heading error (deg) of odometry after one full turn in place."""
    odom = Odometry(np.random.default_rng(seed))
    base = OmniBase(Pose2D(), BaseLimits(), odom)
    base.set_command(0.0, 0.0, 0.5)
    while base.turned < 2 * math.pi:
        base.step(DT)
    err = odom.pose.theta - base.pose.theta
    return math.degrees(math.atan2(math.sin(err), math.cos(err)))


def straight(seed: int, metres: float = 5.0) -> tuple[float, float]:
    odom = Odometry(np.random.default_rng(seed))
    base = OmniBase(Pose2D(), BaseLimits(), odom)
    base.set_command(0.35, 0.0, 0.0)
    while base.travelled < metres:
        base.step(DT)
    return math.degrees(odom.pose.theta - base.pose.theta), odom.pose.x


def test_rotation_drift_about_ten_degrees_per_turn() -> None:
    errors = [rotate_once(seed) for seed in range(8)]
    for e in errors:
        assert 6.0 <= abs(e) <= 14.0, errors
    assert rotate_once(3) == rotate_once(3)
    assert rotate_once(3) != rotate_once(4)


def test_translation_drift_about_one_degree_per_metre() -> None:
    for seed in range(8):
        heading_err, x = straight(seed)
        assert 3.0 <= abs(heading_err) <= 7.0, (seed, heading_err)
        assert abs(x - 5.0) < 0.3
    assert straight(1) == straight(1)
    assert straight(1) != straight(2)


def test_odometry_starts_at_origin_in_odom_frame() -> None:
    odom = Odometry(np.random.default_rng(0))
    base = OmniBase(Pose2D(4.0, 3.0, 1.0), odometry=odom)
    assert odom.pose == Pose2D()
    base.set_command(0.2, 0.0, 0.0)
    run(base, 1.0)
    assert odom.pose.x > 0.05 and abs(odom.pose.y) < 0.01


def test_collision_on_synthetic_grid() -> None:
    grid = GridMap.empty(4.0, 4.0, 0.05)
    grid.data[:, 60:] = 100  # wall from x = 3.0
    free = lambda x, y, r: bool((grid.value_at(np.array([x + r]), np.array([y])) == 0).all())  # noqa: E731
    base = OmniBase(Pose2D(2.0, 2.0, 0.0))
    base.set_command(0.35, 0.0, 0.0)
    run(base, 5.0, free)
    assert base.collisions == 1 and base.pose.x + 0.25 < 3.0
