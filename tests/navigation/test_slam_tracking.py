"""Front-end safeguards of graph SLAM: maps that give way to sharper views, and matches that
may not stray from the odometry guess."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from amiro.core.gridmap import OCCUPIED, GridMap
from amiro.core.messages import Pose2D
from amiro.navigation.graph_slam import GraphSlamParams, tracking_params
from amiro.navigation.occupancy import LogOddsGrid
from amiro.navigation.submaps import SubmapFrontEnd, odometry_window
from amiro.sim.lidar import Lidar


def _crossings_to_free(clamp: float) -> int:
    """Beams that must cross a cell hit 20 times before it reads free."""
    grid = LogOddsGrid(3.0, 2.0, 0.05, (0.0, 0.0), clamp=clamp)
    here = np.array([1.52]), np.array([1.02])
    beyond = np.array([2.52]), np.array([1.02])
    for _ in range(20):
        grid.integrate(0.12, 1.02, *here)
    row, col = round(1.02 / 0.05 - 0.5), round(1.52 / 0.05 - 0.5)
    for n in range(1, 50):
        grid.integrate(0.12, 1.02, *beyond)
        if grid.logodds[row, col] < 0.0:
            return n
    return 50


def test_a_low_clamp_lets_closer_views_redraw_a_wall() -> None:
    assert _crossings_to_free(2.0) <= 6
    assert _crossings_to_free(6.0) >= 15


def test_graph_slam_tracks_with_the_low_clamp_and_the_gate() -> None:
    slam = GraphSlamParams().slam
    assert slam == tracking_params()
    # the gate follows the odometry's uncertainty over the step: under 0.2 m for a short
    # simulated step, decimetres for the metre between two scans of a real log
    short = odometry_window(Pose2D(0.2, 0.0, 0.0), slam)
    long = odometry_window(Pose2D(1.0, 0.0, 0.3), slam)
    assert slam.clamp <= 2.0 and slam.gate_sigmas * short.xy < 0.2
    assert slam.gate_sigmas * long.xy > 0.3


def _room() -> GridMap:
    """A 6 x 4 m room with a box and a pillar, so a scan fixes the pose in every direction."""
    data = np.zeros((80, 120), np.int8)
    data[:2, :] = data[-2:, :] = data[:, :2] = data[:, -2:] = OCCUPIED
    data[50:62, 80:100] = OCCUPIED
    data[15:20, 30:35] = OCCUPIED
    return GridMap(data, 0.05)


def _track_a_false_jump(gate_sigmas: float) -> tuple[Pose2D, SubmapFrontEnd]:
    """Two scans from the same place while odometry claims a 0.2 m step forward."""
    lidar, room = Lidar(), _room()
    params = dataclasses.replace(tracking_params(), gate_sigmas=gate_sigmas)
    front = SubmapFrontEnd(params)
    true = Pose2D(2.0, 2.0, 0.3)
    ranges = lidar.true_ranges(room, true)
    ok = np.isfinite(ranges)
    px = ranges[ok] * np.cos(lidar.angles[ok])
    py = ranges[ok] * np.sin(lidar.angles[ok])
    front.track(px, py, Pose2D())
    front.insert(px, py, keyframe=0)
    return front.track(px, py, Pose2D(0.2, 0.0, 0.0)), front


def test_the_matcher_alone_undoes_the_false_jump() -> None:
    pose, front = _track_a_false_jump(math.inf)
    assert math.hypot(pose.x, pose.y) < 0.03
    assert front.refused == 0


def test_a_match_far_from_the_odometry_guess_is_refused() -> None:
    pose, front = _track_a_false_jump(tracking_params().gate_sigmas)
    assert abs(pose.x - 0.2) < 1e-9 and abs(pose.y) < 1e-9
    assert front.refused == 1


def test_without_odometry_the_front_end_predicts_with_constant_velocity() -> None:
    # 0.7 m steps, turning 29 degrees back and forth: beyond Gauss-Newton's basin from a
    # standing-still guess (a log without odometry, as Orebro)
    lidar, room = Lidar(), _room()
    front = SubmapFrontEnd(tracking_params())
    truth = [Pose2D(0.8 + 0.7 * k, 2.0, 0.5 * (k % 2)) for k in range(8)]
    poses = []
    for k, true in enumerate(truth):
        ranges = lidar.true_ranges(room, true)
        ok = np.isfinite(ranges)
        px = ranges[ok] * np.cos(lidar.angles[ok])
        py = ranges[ok] * np.sin(lidar.angles[ok])
        poses.append(front.track(px, py, None))
        front.insert(px, py, keyframe=k)
    for true, pose in zip(truth, poses, strict=True):
        assert math.hypot(pose.x - (true.x - 0.8), pose.y - (true.y - 2.0)) < 0.05
        assert abs(pose.theta - true.theta) < 0.02
