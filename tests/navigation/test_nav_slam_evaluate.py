"""``amiro slam evaluate``: the relation error of Kümmerle et al., Pepper-like drift on a
reference trajectory, and the command over a folder of logs."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from amiro.cli import main
from amiro.core.messages import Pose2D
from amiro.evaluation.slam_evaluate import pepper_odometry, relation_error, relation_pairs
from amiro.home.world import World, default_home_path
from amiro.navigation.metrics import ate_rmse
from amiro.sim.carmen_log import write_log

ROUTE = [(0.8, 1.0), (2.0, 1.0), (2.0, 4.2), (6.8, 4.2)]


def _line(n: int, step: float) -> list[Pose2D]:
    return [Pose2D(k * step, 0.0, 0.0) for k in range(n)]


def test_relations_pair_each_scan_with_the_first_one_a_metre_further() -> None:
    assert relation_pairs(_line(10, 0.25))[:2] == [(0, 4), (1, 5)]
    assert relation_pairs(_line(10, 0.25))[-1] == (5, 9)
    assert relation_pairs(_line(3, 1.0)) == [(0, 1), (1, 2)]


def test_relation_error_ignores_the_frame_and_sees_a_local_error() -> None:
    ref = [Pose2D(k * 0.5, math.sin(k), 0.1 * k) for k in range(12)]
    pairs = relation_pairs(ref)
    c, s = math.cos(0.7), math.sin(0.7)
    moved = [Pose2D(3 + c * p.x - s * p.y, -1 + s * p.x + c * p.y, p.theta + 0.7) for p in ref]
    assert relation_error(moved, ref, pairs).trans_mean < 1e-9
    bent = list(ref)
    bent[5] = Pose2D(ref[5].x + 0.2, ref[5].y, ref[5].theta + 0.05)
    err = relation_error(bent, ref, pairs)
    assert err.trans_mean > 0.01 and err.rot_mean_deg > 0.1


def test_pepper_drift_is_seeded_and_bends_a_square() -> None:
    side = [Pose2D(0.2 * k, 0.0, 0.0) for k in range(50)]
    square = []
    for turn in range(4):
        c, s = math.cos(turn * math.pi / 2), math.sin(turn * math.pi / 2)
        ox, oy = (0.0, 10.0, 10.0, 0.0)[turn], (0.0, 0.0, 10.0, 10.0)[turn]
        square += [Pose2D(ox + c * p.x, oy + s * p.x, turn * math.pi / 2) for p in side]
    a, b = pepper_odometry(square, seed=3), pepper_odometry(square, seed=3)
    assert a == b
    ref = np.array([[p.x, p.y] for p in square])
    assert ate_rmse(np.array([[p.x, p.y] for p in a]), ref) > 0.2


def test_evaluate_scores_every_log_and_writes_a_plot_per_run(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    world = World.load(default_home_path())
    logs = tmp_path / "logs"
    logs.mkdir()
    n = write_log(logs / "apt.log", world.live, ROUTE, np.random.default_rng(0))
    (logs / "notes.txt").write_text("not a log")
    out = tmp_path / "out"
    assert main(["slam", "evaluate", str(logs), "--out", str(out), "--json"]) == 0
    captured = capsys.readouterr()
    result = json.loads(captured.out)
    assert "apt" in captured.err  # progress
    rows = result["logs"]
    assert [(r["log"], r["odometry"]) for r in rows] == [("apt", "real"), ("apt", "pepper")]
    for row in rows:
        assert row["scans"] == n
        assert row["ate_rmse_m"] < row["odom_ate_rmse_m"]
        assert 0.0 < row["rel_trans_m"] < 0.1
        assert row["log_scans_per_s"] == pytest.approx(2.0, rel=0.01)
        assert Path(row["plot"]).is_file()
    assert (out / "apt-real-map.png").is_file()
    assert set(result["summary"]) == {"real", "pepper"}
