"""AMCL, Hector-style SLAM, CARMEN logs and trajectory metrics on the simulated apartment."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from amiro.core.config import ConfigError
from amiro.core.messages import LaserScan, Pose2D
from amiro.home.world import World, default_home_path
from amiro.navigation.amcl import AmclParams, ParticleFilter
from amiro.navigation.carmen import read_carmen
from amiro.navigation.likelihood import LikelihoodField
from amiro.navigation.metrics import ate_rmse, dtw, resample
from amiro.navigation.slam_run import run_slam
from amiro.sim.carmen_log import write_log
from amiro.sim.lidar import Lidar

ROUTE = [(0.8, 1.0), (2.0, 1.0), (2.0, 4.2), (6.8, 4.2), (5.0, 4.2), (5.0, 2.0), (8.5, 2.0)]


def _scan(world: World, pose: Pose2D, rng: np.random.Generator) -> LaserScan:
    return Lidar().scan(world.live, pose, 0.0, rng)


def test_amcl_tracks_a_known_start_and_corrects_a_wrong_guess() -> None:
    world = World.load(default_home_path())
    rng = np.random.default_rng(0)
    pf = ParticleFilter(LikelihoodField(world.live), rng, AmclParams())
    truth = Pose2D(2.0, 4.2, 0.0)
    pf.init_pose(Pose2D(2.15, 4.1, 0.08))  # off by 0.18 m and 4.6 degrees
    pf.predict(Pose2D())
    for _ in range(8):
        pf.correct(_scan(world, truth, rng))
    est = pf.estimate()
    assert est.distance_to(truth) < 0.06
    assert abs(est.theta - truth.theta) < 0.03


def test_slam_over_a_simulated_carmen_log_beats_odometry(tmp_path: Path) -> None:
    world = World.load(default_home_path())
    log = tmp_path / "apt.log"
    n = write_log(log, world.live, ROUTE, np.random.default_rng(0))
    scans = read_carmen(log)
    assert len(scans) == n and len(scans[0].ranges) == 181
    res = run_slam(log, tmp_path / "out")
    assert res["scans"] == n
    assert res["ate_rmse_m"] < 0.15
    assert res["odom_ate_rmse_m"] > 2 * res["ate_rmse_m"]
    rows = (tmp_path / "out" / "trajectory.csv").read_text().splitlines()
    assert rows[0] == "timestamp,x,y,theta" and len(rows) == n + 1
    assert (tmp_path / "out" / "map.pgm").is_file()


def test_carmen_reader_rejects_bad_input(tmp_path: Path) -> None:
    with pytest.raises(ConfigError):
        read_carmen(tmp_path / "missing.log")
    bad = tmp_path / "bad.log"
    bad.write_text("FLASER 3 1.0 2.0\n")
    with pytest.raises(ConfigError, match="malformed"):
        read_carmen(bad)


def test_ate_ignores_a_rigid_offset_and_dtw_grows_with_deviation() -> None:
    t = np.linspace(0, 2 * math.pi, 50)
    ref = np.column_stack((np.cos(t), np.sin(t)))
    c, s = math.cos(0.7), math.sin(0.7)
    moved = ref @ np.array([[c, s], [-s, c]]) + [3.0, -1.0]
    assert ate_rmse(moved, ref) < 1e-9
    assert ate_rmse(moved + [[0.1, 0.0]] * np.sign(ref[:, :1]), ref) > 0.05
    line = resample([Pose2D(0, 0), Pose2D(3, 0)])
    assert dtw(line, line) == 0.0
    near = resample([Pose2D(0, 0.1), Pose2D(3, 0.1)])
    far = resample([Pose2D(0, 0.3), Pose2D(3, 0.3)])
    assert 0.0 < dtw(line, near) < dtw(line, far)
