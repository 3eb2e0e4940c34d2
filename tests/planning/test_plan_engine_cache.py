"""The pyperplan engine keeps grounded tasks: re-plans must equal plans of a fresh planner."""

from __future__ import annotations

import numpy as np
import pytest
from up_pyperplan.engine import EngineImpl  # type: ignore[import-untyped]

from amiro.behavior.planning.config import PlanningConfig
from amiro.behavior.planning.domain import home_domain
from amiro.behavior.planning.knowledge import DoorState, KnowledgeBase
from amiro.behavior.planning.planner import HomePlanner, solve
from amiro.behavior.planning.problem import Goal, RobotState, make_problem
from amiro.behavior.planning.topology import grid_topology, topology_from_world
from amiro.home.world import World, default_home_path

DOCK = RobotState("hallway", 0.8, 1.0)
PYPERPLAN = PlanningConfig(engine="pyperplan")
GOAL = [Goal("notified", "maria")]


@pytest.fixture
def kb() -> KnowledgeBase:
    topo = topology_from_world(World.load(default_home_path()))
    return KnowledgeBase(topo, {"maria": "living_room", "john": "hallway"})


def fresh_plan(kb: KnowledgeBase, robot: RobotState, goals: list[Goal]) -> list[str]:
    return [str(s) for s in HomePlanner(PYPERPLAN).plan(kb, robot, goals).steps]


def test_replan_after_a_door_closed_reuses_the_grounding_and_matches_a_fresh_plan(
    kb: KnowledgeBase,
) -> None:
    planner = HomePlanner(PYPERPLAN)
    before = planner.plan(kb, DOCK, GOAL)
    kb.set_door("living_door", DoorState.CLOSED, 1.0, "lidar")
    after = planner.plan(kb, DOCK, GOAL)
    assert planner._engine.cache_hits == 1
    assert [str(s) for s in after.steps] == fresh_plan(kb, DOCK, GOAL)
    assert [str(s) for s in after.steps] != [str(s) for s in before.steps]
    assert any(s.action == "ask_open_door" for s in after.steps)


def test_a_changed_static_fact_grounds_again(kb: KnowledgeBase) -> None:
    planner = HomePlanner(PYPERPLAN)
    planner.plan(kb, DOCK, GOAL)
    kb.set_door("living_door", DoorState.CLOSED, 1.0, "lidar")
    kb.declined("john", 2.0)  # who is willing to help is static to pyperplan
    outcome = planner.plan(kb, DOCK, GOAL)
    assert planner._engine.cache_hits == 0
    assert [str(s) for s in outcome.steps] == fresh_plan(kb, DOCK, GOAL)
    assert not any(s.action == "ask_open_door" for s in outcome.steps)


def test_cached_engine_agrees_with_up_pyperplan_on_generated_homes() -> None:
    rng = np.random.default_rng(3)
    domain = home_domain()
    planner = HomePlanner(PYPERPLAN)
    solved = 0
    for n_rooms in (3, 6, 9):
        topo = grid_topology(n_rooms, rng)
        kb = KnowledgeBase(topo, {"resident": topo.rooms[-1], "helper": topo.rooms[0]})
        wp = topo.waypoints[f"{topo.rooms[0]}_centre"]
        robot = RobotState(topo.rooms[0], wp.x, wp.y)
        goals = [Goal("notified", "resident"), Goal("activity_checked", "resident")]
        for door in list(topo.doors)[:2]:
            kb.set_door(door, DoorState.CLOSED, 1.0, "test")
            ours = planner.plan(kb, robot, goals)
            reference = solve(EngineImpl(), make_problem(domain, kb, robot, goals), None)
            assert ours.solved == reference[0].startswith("SOLVED")
            assert len(ours.steps) == len(reference[1])
            solved += ours.solved
    assert 0 < solved < 6  # both kinds of outcome were compared
