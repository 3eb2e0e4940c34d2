"""The section-4.3 experiments: single runs against the issue's targets, and their scoring."""

from __future__ import annotations

import argparse

import pytest

from amiro.commands.navigation import register
from amiro.core.config import ConfigError
from amiro.core.messages import Pose2D
from amiro.evaluation.navigation_experiments import (
    EXPERIMENTS,
    Experiment,
    RunResult,
    _summary,
    followed_plan,
    format_table,
    run_once,
)

BY_NAME = {e.name: e for e in EXPERIMENTS}


def test_forward_run_meets_the_targets() -> None:
    exp = BY_NAME["forward"]
    run = run_once(exp, seed=1, max_speed=0.45)
    assert run.arrived and run.collisions == 0
    assert run.time_s <= exp.paper["time_s"]
    assert run.dtw <= exp.paper["dtw"] / 2.0
    assert run.plan_m == pytest.approx(2.7, abs=0.1)
    assert run.travelled_m == pytest.approx(run.plan_m, abs=0.15)
    assert run.replans == 0


def test_slalom_between_two_mapped_obstacles() -> None:
    exp = BY_NAME["two_obstacles"]
    run = run_once(exp, seed=2, max_speed=0.45)
    assert run.arrived and run.collisions == 0
    assert run.time_s <= exp.paper["time_s"]
    assert run.dtw <= exp.paper["dtw"] / 2.0
    # a slalom is longer than the 2.7 m straight line
    assert run.plan_m > 3.0 and run.travelled_m > 3.0


def test_hallway_boxes_not_in_the_map_force_replanning() -> None:
    exp = BY_NAME["hallway_obstacles"]
    assert not exp.mapped
    run = run_once(exp, seed=3, max_speed=0.45)
    assert run.arrived and run.collisions == 0
    assert run.replans >= 1
    assert run.time_s <= exp.paper["time_s"]
    assert run.travelled_m > 17.0


def test_followed_plan_cuts_each_replaced_plan_where_the_robot_was() -> None:
    first = [Pose2D(0.0, 0.0), Pose2D(4.0, 0.0)]
    second = [Pose2D(1.0, 0.0), Pose2D(1.0, 2.0)]
    track = [(0.0, Pose2D(0.0, 0.0)), (1.0, Pose2D(1.0, 0.0)), (2.0, Pose2D(1.0, 1.0))]
    plan = followed_plan([(0.0, first), (1.0, second)], track)
    xs = [p.x for p in plan]
    assert max(xs) == pytest.approx(1.0)  # the rest of the first plan was never followed
    assert plan[-1] == second[-1]


def test_summary_flags_a_missed_target() -> None:
    exp = Experiment("forward", "lab_area", paper={"time_s": 8.0, "dtw": 2.0})
    good = RunResult(True, 2.7, 2.7, 7.0, 0.5, 0.4, 0, 0)
    slow = RunResult(True, 2.7, 2.7, 9.5, 0.5, 0.4, 0, 0)
    assert _summary(exp, [good, good])["targets_met"]
    row = _summary(exp, [good, slow])
    assert not row["targets_met"] and row["time_s"] == pytest.approx(8.25)
    assert not _summary(exp, [RunResult(True, 2.7, 2.7, 7.0, 1.5, 0.4, 0, 0)])["targets_met"]
    table = format_table(
        {
            "experiments": [row],
            "trajectory": "slam",
            "localization": "amcl",
            "dtw_spacing_m": 0.1,
            "max_speed": 0.45,
        }
    )
    assert "8.25 / 8.00" in table


@pytest.mark.parametrize("argv", [["--runs", "0"], ["--max-speed", "0.9"]])
def test_cli_rejects_bad_options(argv: list[str]) -> None:
    parser = argparse.ArgumentParser()
    register(parser.add_subparsers())
    args = parser.parse_args(["nav", "experiments", *argv])
    with pytest.raises(ConfigError):
        args.handler(args)
