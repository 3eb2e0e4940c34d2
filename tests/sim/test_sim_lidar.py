"""Lidar ray casting: geometry, limits, noise and live world changes."""

from __future__ import annotations

import math

import numpy as np
import pytest

from amiro.core.gridmap import GridMap
from amiro.core.messages import Pose2D
from amiro.home.world import World, default_home_path
from amiro.sim.lidar import Lidar, LidarParams


def box_room() -> GridMap:
    """A 6 m x 4 m room with 0.1 m walls: free inside x in [0.1, 5.9], y in [0.1, 3.9]."""
    g = GridMap.empty(6.0, 4.0, 0.05)
    g.data[:2, :] = g.data[-2:, :] = 100
    g.data[:, :2] = g.data[:, -2:] = 100
    return g


def beam(scan_angles: np.ndarray, angle: float) -> int:
    d = np.angle(np.exp(1j * (scan_angles - angle)))
    return int(np.argmin(np.abs(d)))


def test_ranges_in_a_box_room() -> None:
    lidar = Lidar()
    pose = Pose2D(2.0, 1.5, 0.0)
    scan = lidar.scan(box_room(), pose, 1.0, np.random.default_rng(0))
    a = scan.angles()
    assert len(scan.ranges) == 360 and scan.header.frame_id == "laser"
    assert scan.angle_increment == pytest.approx(math.radians(1.0))
    expect = {0.0: 5.9 - 2.0, math.pi / 2: 3.9 - 1.5, math.pi: 2.0 - 0.1, -math.pi / 2: 1.4}
    for ang, dist in expect.items():
        r = scan.ranges[beam(a, ang)]
        assert r == pytest.approx(dist, abs=0.03 + 3 * 0.01 * dist), ang
    # rotating the robot rotates the scan
    scan2 = lidar.scan(box_room(), Pose2D(2.0, 1.5, math.pi / 2), 1.0)
    assert scan2.ranges[beam(a, 0.0)] == pytest.approx(2.4, abs=0.03)


def test_noise_is_seeded_and_about_one_percent() -> None:
    lidar = Lidar()
    g, pose = box_room(), Pose2D(2.0, 1.5, 0.0)
    truth = lidar.true_ranges(g, pose)
    s1 = lidar.scan(g, pose, 0.0, np.random.default_rng(7)).ranges
    s2 = lidar.scan(g, pose, 0.0, np.random.default_rng(7)).ranges
    s3 = lidar.scan(g, pose, 0.0, np.random.default_rng(8)).ranges
    assert np.array_equal(s1, s2) and not np.array_equal(s1, s3)
    rel = (s1 - truth) / truth
    assert 0.005 < rel.std() < 0.015


def test_min_and_max_range() -> None:
    g = GridMap.empty(30.0, 4.0, 0.05)
    g.data[:2, :] = g.data[-2:, :] = 100
    g.data[:, -2:] = 100
    lidar = Lidar()
    scan = lidar.scan(g, Pose2D(1.0, 0.22, 0.0), 0.0)
    a = scan.angles()
    assert scan.ranges[beam(a, math.pi)] == math.inf  # open end: no return (REP-117 +inf)
    assert scan.ranges[beam(a, 0.0)] == math.inf  # far wall at 28.9 m > 12 m
    assert scan.ranges[beam(a, -math.pi / 2)] == -math.inf  # 0.12 m < range_min
    assert scan.range_min == 0.15 and scan.range_max == 12.0
    finite = scan.ranges[np.isfinite(scan.ranges)]
    assert ((finite >= 0.15) & (finite <= 12.0)).all()


def test_rate_limits() -> None:
    assert Lidar(LidarParams(rate=5.5)).params.rate == 5.5
    with pytest.raises(ValueError):
        LidarParams(rate=20.0)


def test_closing_a_door_changes_the_scan() -> None:
    world = World.load(default_home_path())
    lidar = Lidar()
    pose = Pose2D(1.45, 4.2, 0.0)  # in the hallway, below the bedroom door
    up = beam(lidar.angles, math.pi / 2)
    open_scan = lidar.true_ranges(world.live, pose)
    world.set_door("bedroom_door", False)
    closed_scan = lidar.true_ranges(world.live, pose)
    assert open_scan[up] == pytest.approx(2.0, abs=0.05)  # through the door to the bed
    assert closed_scan[up] == pytest.approx(5.0 - 0.05 - 4.2, abs=0.03)
