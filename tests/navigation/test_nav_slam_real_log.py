"""SLAM on a real lidar log with its real odometry (Freiburg building 101, 292 scans a metre
apart), read from ../shared/data beside the repository (research terms: never copied in)."""

from __future__ import annotations

import itertools
from pathlib import Path

import numpy as np
import pytest

from amiro.evaluation.slam_evaluate import evaluate_log
from amiro.navigation.carmen import read_carmen
from amiro.navigation.metrics import ate_rmse
from amiro.navigation.poses import between
from shared_data import shared_data


@pytest.fixture
def log() -> Path:
    return shared_data("slam", "carmen", "freiburg-101-corrected.log.gz")


def test_the_reader_recovers_the_odometry_the_robot_measured(log: Path) -> None:
    scans = read_carmen(log)
    assert len(scans) == 292
    # step by step the raw odometry agrees with gmapping's corrected motion to centimetres,
    # while over the whole run it has drifted by metres
    errors = []
    for a, b in itertools.pairwise(scans):
        assert a.reference is not None and b.reference is not None
        d_ref, d_odo = between(a.reference, b.reference), between(a.odom, b.odom)
        errors.append(np.hypot(d_ref.x - d_odo.x, d_ref.y - d_odo.y))
    assert np.median(errors) < 0.06 and np.max(errors) < 0.3
    odo = np.array([[s.odom.x, s.odom.y] for s in scans])
    ref = np.array([[s.reference.x, s.reference.y] for s in scans if s.reference])
    assert ate_rmse(odo, ref) > 2.0


def test_slam_with_the_real_odometry_holds(log: Path) -> None:
    (row,) = evaluate_log(log, None, ("real",))
    assert row["ate_rmse_m"] < 0.25
    assert row["rel_trans_m"] < 0.07
    assert row["loop_closures"] > 0
