"""Planning time on generated homes of growing size (issue target: < 100 ms for 10 rooms).

Two figures per home: *cold*, a new planner's first plan (problem conversion, grounding and
search), and *re-plan*, the same planner planning again after a door closed (the grounded task
is kept, only the search runs from the new state).  The target is checked on the cold figure.
"""

from __future__ import annotations

import statistics
import time
from typing import Any

import numpy as np

from amiro.behavior.planning.config import PlanningConfig
from amiro.behavior.planning.knowledge import DoorState, KnowledgeBase
from amiro.behavior.planning.planner import HomePlanner, PlanOutcome
from amiro.behavior.planning.problem import Goal, RobotState
from amiro.behavior.planning.topology import grid_topology

SIZES = (5, 10, 20)


def bench_home(
    n_rooms: int, config: PlanningConfig, rng: np.random.Generator, trials: int
) -> dict[str, Any]:
    """Deliver to a person in the far corner from the first room: ``trials`` cold plans,
    each followed by a re-plan once a door of the plan is found closed."""
    topo = grid_topology(n_rooms, rng)
    start = topo.waypoints[f"{topo.rooms[0]}_centre"]
    robot = RobotState(topo.rooms[0], start.x, start.y)
    goals = [Goal("notified", "resident")]
    cold, replan, steps = [], [], 0
    for _ in range(trials):
        kb = KnowledgeBase(topo, {"resident": topo.rooms[-1], "helper": topo.rooms[0]})
        planner = HomePlanner(config)
        ms, outcome = _timed(planner, kb, robot, goals)
        cold.append(ms)
        steps = len(outcome.steps)
        crossed = next((s.args[0] for s in outcome.steps if s.action == "cross"), None)
        if crossed is not None:
            kb.set_door(crossed, DoorState.CLOSED, t=1.0, source="bench")
        replan.append(_timed(planner, kb, robot, goals)[0])
    return {
        "rooms": n_rooms,
        "doors": len(topo.doors),
        "waypoints": len(topo.waypoints),
        "plan_steps": steps,
        "ms_median": round(statistics.median(cold), 1),
        "ms_min": round(min(cold), 1),
        "replan_ms_median": round(statistics.median(replan), 1),
    }


def _timed(
    planner: HomePlanner, kb: KnowledgeBase, robot: RobotState, goals: list[Goal]
) -> tuple[float, PlanOutcome]:
    started = time.perf_counter()
    outcome = planner.plan(kb, robot, goals)
    return (time.perf_counter() - started) * 1000.0, outcome


def run_bench(config: PlanningConfig, seed: int = 0, trials: int = 5) -> dict[str, Any]:
    rng = np.random.default_rng(seed)
    HomePlanner(config).plan(*_warm_up())  # imports and engine start-up are not planning time
    homes = [bench_home(n, config, rng, trials) for n in SIZES]
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
