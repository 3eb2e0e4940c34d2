"""Pose-graph back end: analytic Jacobian, loop closing, and a false loop edge ignored."""

from __future__ import annotations

import math

import numpy as np

from amiro.core.messages import Pose2D
from amiro.navigation.posegraph import PoseGraph, _residuals_and_jacobian
from amiro.navigation.poses import between, compose


def test_jacobian_matches_finite_differences() -> None:
    rng = np.random.default_rng(0)
    poses = rng.normal(size=(5, 3))
    ii, jj = np.array([0, 1, 2, 0]), np.array([1, 2, 3, 4])
    z = rng.normal(size=(4, 3)) * 0.3
    sqrt_info = rng.uniform(1.0, 3.0, size=(4, 3))
    res, jac = _residuals_and_jacobian(poses, ii, jj, z, sqrt_info)
    numeric = np.zeros(jac.shape)
    for k in range(poses.size):
        moved = poses.reshape(-1).copy()
        moved[k] += 1e-6
        r2, _ = _residuals_and_jacobian(moved.reshape(5, 3), ii, jj, z, sqrt_info, False)
        numeric[:, k] = (r2 - res).reshape(-1) / 1e-6
    assert np.abs(numeric - jac.toarray()).max() < 1e-4


def _drifting_loop(outlier: bool) -> tuple[PoseGraph, list[Pose2D]]:
    """20 steps round a pentagon-like loop with biased odometry, closed by one loop edge."""
    step = Pose2D(1.0, 0.0, 2 * math.pi / 20)
    truth = [Pose2D()]
    for _ in range(20):
        truth.append(compose(truth[-1], step))
    graph = PoseGraph()
    graph.add_node(truth[0])
    noisy = Pose2D(1.03, 0.0, step.theta + 0.03)
    for k in range(20):
        graph.add_node(compose(graph.pose(k), noisy))
        graph.add_edge(k, k + 1, noisy, (0.05, 0.05, 0.03))
    graph.add_edge(0, 20, between(truth[0], truth[20]), (0.01, 0.01, 0.01), robust=True)
    if outlier:
        graph.add_edge(3, 15, Pose2D(5.0, 5.0, 1.0), (0.01, 0.01, 0.01), robust=True)
    return graph, truth


def _max_error(graph: PoseGraph, truth: list[Pose2D]) -> float:
    return max(graph.pose(k).distance_to(p) for k, p in enumerate(truth))


def test_a_loop_edge_pulls_the_drifted_loop_back() -> None:
    graph, truth = _drifting_loop(outlier=False)
    before = _max_error(graph, truth)
    graph.optimize()
    assert before > 1.0
    assert _max_error(graph, truth) < 0.25 * before
    assert graph.pose(0) == truth[0]  # the first node anchors the map frame


def test_a_false_loop_edge_is_down_weighted() -> None:
    clean, truth = _drifting_loop(outlier=False)
    clean.optimize()
    spoiled, _ = _drifting_loop(outlier=True)
    spoiled.optimize()
    assert abs(_max_error(spoiled, truth) - _max_error(clean, truth)) < 0.05
