"""Planning time on generated homes of growing size (issue target: < 100 ms for 10 rooms)."""

from __future__ import annotations

import statistics
import time
from typing import Any

import numpy as np

from amiro.behavior.planning.knowledge import KnowledgeBase
from amiro.behavior.planning.planner import HomePlanner, PlanningConfig
from amiro.behavior.planning.problem import Goal, RobotState
from amiro.behavior.planning.topology import grid_topology

SIZES = (5, 10, 20)


def bench_home(
    n_rooms: int, planner: HomePlanner, rng: np.random.Generator, trials: int
) -> dict[str, Any]:
    """Deliver to a person in the far corner from the first room, ``trials`` times."""
    topo = grid_topology(n_rooms, rng)
    far = topo.rooms[-1]
    kb = KnowledgeBase(topo, {"resident": far, "helper": topo.rooms[0]})
    start = topo.waypoints[f"{topo.rooms[0]}_centre"]
    robot = RobotState(topo.rooms[0], start.x, start.y)
    goals = [Goal("notified", "resident")]
    times, steps = [], 0
    for _ in range(trials):
        started = time.perf_counter()
        outcome = planner.plan(kb, robot, goals)
        times.append((time.perf_counter() - started) * 1000.0)
        steps = len(outcome.steps)
    return {
        "rooms": n_rooms,
        "doors": len(topo.doors),
        "waypoints": len(topo.waypoints),
        "plan_steps": steps,
        "ms_median": round(statistics.median(times), 1),
        "ms_min": round(min(times), 1),
    }


def run_bench(config: PlanningConfig, seed: int = 0, trials: int = 5) -> dict[str, Any]:
    planner = HomePlanner(config)
    rng = np.random.default_rng(seed)
    planner.plan(*_warm_up())  # imports and engine start-up are not planning time
    homes = [bench_home(n, planner, rng, trials) for n in SIZES]
    ten = next(h for h in homes if h["rooms"] == 10)
    return {
        "engine": config.engine,
        "temporal": config.temporal,
        "trials": trials,
        "homes": homes,
        "target_ms_10_rooms": 100.0,
        "meets_target": ten["ms_median"] < 100.0,
    }


def _warm_up() -> tuple[KnowledgeBase, RobotState, list[Goal]]:
    topo = grid_topology(2, np.random.default_rng(0))
    kb = KnowledgeBase(topo, {"resident": topo.rooms[1]})
    wp = topo.waypoints[f"{topo.rooms[0]}_centre"]
    return kb, RobotState(topo.rooms[0], wp.x, wp.y), [Goal("notified", "resident")]
