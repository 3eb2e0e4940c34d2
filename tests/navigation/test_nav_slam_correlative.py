"""Correlative scan matching: finds a pose far outside Gauss-Newton's basin, flags aliases."""

from __future__ import annotations

import math

import numpy as np

from amiro.core.messages import Pose2D
from amiro.home.world import World, default_home_path
from amiro.navigation.correlative import CorrelativeMatcher, SearchWindow
from amiro.navigation.occupancy import LogOddsGrid
from amiro.sim.lidar import Lidar, LidarParams


def _mapped(world: World, poses: list[Pose2D]) -> LogOddsGrid:
    lidar = Lidar(LidarParams(noise=0.0))
    grid = LogOddsGrid(14.0, 10.0, 0.05, (-1.0, -1.0))
    for pose in poses:
        r = lidar.true_ranges(world.live, pose)
        ok = np.isfinite(r)
        th = pose.theta + lidar.angles[ok]
        for _ in range(3):
            grid.integrate(pose.x, pose.y, pose.x + r[ok] * np.cos(th), pose.y + r[ok] * np.sin(th))
    return grid


def test_finds_the_pose_metres_away_from_the_guess() -> None:
    world = World.load(default_home_path())
    truth = world.place("hallway")
    grid = _mapped(world, [truth])
    lidar = Lidar()
    scan = lidar.scan(world.live, truth, 0.0, np.random.default_rng(0)).ranges
    ok = np.isfinite(scan)
    px, py = scan[ok] * np.cos(lidar.angles[ok]), scan[ok] * np.sin(lidar.angles[ok])
    matcher = CorrelativeMatcher(grid.prob, grid.resolution, grid.origin)
    guess = Pose2D(truth.x + 1.2, truth.y - 0.9, truth.theta + math.radians(6))
    found = matcher.match(px, py, guess, SearchWindow(2.0, math.radians(10)))
    assert found.pose.distance_to(truth) < 0.08
    assert abs(found.pose.theta - truth.theta) < math.radians(1.5)
    assert found.score > 0.6
    assert found.runner_up < 0.9 * found.score  # the apartment is not self-similar


def test_a_featureless_corridor_is_reported_ambiguous() -> None:
    prob = np.full((60, 400), 0.5, np.float32)  # 3 m x 20 m, walls along both sides
    prob[5:55, :] = 0.1
    prob[5, :] = prob[54, :] = 0.95
    matcher = CorrelativeMatcher(prob, 0.05, (0.0, 0.0))
    xs = np.linspace(-3.0, 3.0, 61)
    px = np.concatenate((xs, xs))
    py = np.concatenate((np.full(61, -1.22), np.full(61, 1.23)))
    found = matcher.match(px, py, Pose2D(10.0, 1.5, 0.0), SearchWindow(2.0, 0.05))
    assert found.score > 0.6
    assert found.runner_up > 0.95 * found.score


def test_a_window_of_metres_is_searched_level_by_level() -> None:
    # a big loop: the estimate 5 m and 12 degrees off, searched over +-7 m and +-15 degrees
    world = World.load(default_home_path())
    truth = world.place("hallway")
    grid = _mapped(world, [truth])
    lidar = Lidar()
    scan = lidar.scan(world.live, truth, 0.0, np.random.default_rng(0)).ranges
    ok = np.isfinite(scan)
    px, py = scan[ok] * np.cos(lidar.angles[ok]), scan[ok] * np.sin(lidar.angles[ok])
    matcher = CorrelativeMatcher(grid.prob, grid.resolution, grid.origin)
    guess = Pose2D(truth.x - 3.0, truth.y + 4.0, truth.theta - math.radians(12))
    found = matcher.match(px, py, guess, SearchWindow(7.0, math.radians(15)))
    assert found.pose.distance_to(truth) < 0.08
    assert abs(found.pose.theta - truth.theta) < math.radians(1.5)
    assert found.runner_up < 0.9 * found.score
