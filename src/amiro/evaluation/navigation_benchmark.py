"""``amiro nav benchmark``: random feasible start/goal pairs on any map_server map.

Each trial plans with A* and drives the simulated omni base (limits, accelerations and
bump-stop collisions of ``OmniBase``) with the follower and the DWA at 10 Hz, on the true
pose: it measures planning and control, not localisation.
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from amiro.core.gridmap import GridMap
from amiro.core.messages import Pose2D
from amiro.navigation.config import NavigationConfig
from amiro.navigation.dwa import DwaParams, DynamicWindow
from amiro.navigation.follower import FollowerLimits, PathFollower
from amiro.navigation.metrics import path_length
from amiro.navigation.planner import GlobalPlanner
from amiro.navigation.stack import costmap_from_map
from amiro.sim.base import OmniBase

CONTROL_DT = 0.1
PHYSICS_STEPS = 2


def _free_test(grid: GridMap) -> Any:
    """(x, y, r) -> no occupied/unknown cell within r: the base's collision check."""
    from scipy import ndimage

    dist = ndimage.distance_transform_edt(grid.data == 0) * grid.resolution

    def is_free(x: float, y: float, radius: float) -> bool:
        col, row = grid.world_to_cell(x, y)
        if not bool(grid.in_bounds(col, row)):
            return False
        return bool(dist[int(row), int(col)] > radius)

    return is_free


def run_benchmark(grid: GridMap, trials: int, rng: np.random.Generator) -> dict[str, Any]:
    cfg = NavigationConfig()
    costmap = costmap_from_map(grid, cfg)
    planner = GlobalPlanner(costmap)
    limits = FollowerLimits(max_speed=cfg.max_speed, max_turn=cfg.max_turn)
    dwa = DynamicWindow(costmap, DwaParams(max_speed=cfg.max_speed, max_turn=cfg.max_turn))
    is_free = _free_test(grid)
    free_cells = np.argwhere(costmap.clearance > costmap.inscribed + 0.1)
    results: list[dict[str, Any]] = []
    while len(results) < trials:
        a, b = free_cells[rng.integers(0, len(free_cells), 2)]
        start = Pose2D(
            *costmap.frame.to_world(int(a[0]), int(a[1])), float(rng.uniform(-math.pi, math.pi))
        )
        goal = Pose2D(
            *costmap.frame.to_world(int(b[0]), int(b[1])), float(rng.uniform(-math.pi, math.pi))
        )
        if start.distance_to(goal) < 2.0:
            continue
        t0 = time.perf_counter()  # wall time only to measure planning speed
        path = planner.plan_to_pose(start, goal)
        plan_ms = 1000.0 * (time.perf_counter() - t0)
        if path is None:
            continue  # not a feasible pair
        results.append(_drive(start, path, limits, dwa, is_free, plan_ms))
    ok = [r for r in results if r["success"]]
    return {
        "trials": trials,
        "success_rate": round(len(ok) / trials, 4),
        "collisions": int(sum(r["collisions"] for r in results)),
        "path_ratio_mean": round(float(np.mean([r["ratio"] for r in ok])), 4) if ok else None,
        "time_s_mean": round(float(np.mean([r["time"] for r in ok])), 2) if ok else None,
        "plan_ms_mean": round(float(np.mean([r["plan_ms"] for r in results])), 2),
    }


def _drive(
    start: Pose2D,
    path: list[Pose2D],
    limits: FollowerLimits,
    dwa: DynamicWindow,
    is_free: Any,
    plan_ms: float,
) -> dict[str, Any]:
    base = OmniBase(start)
    follower = PathFollower(limits)
    follower.set_path(path)
    plan_m = path_length([start, *path])
    budget = 3.0 * plan_m / limits.max_speed + 30.0
    t = 0.0
    arrived = False
    while t < budget and base.collisions == 0:
        twist, arrived = follower.command(base.pose)
        if arrived:
            break
        cmd = dwa.command(base.pose, base.velocity, twist, path[-1])
        base.set_command(cmd.linear.x, cmd.linear.y, cmd.angular.z)
        for _ in range(PHYSICS_STEPS):
            base.step(CONTROL_DT / PHYSICS_STEPS, is_free)
        t += CONTROL_DT
    return {
        "success": arrived and base.collisions == 0,
        "collisions": base.collisions,
        "ratio": base.travelled / max(plan_m, 1e-9),
        "time": t,
        "plan_ms": plan_ms,
    }
