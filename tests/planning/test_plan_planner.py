"""Plans on the default apartment: the direct way, asking for help, a detour, no plan."""

from __future__ import annotations

import pytest

from amiro.behavior.planning.config import PlanningConfig
from amiro.behavior.planning.knowledge import DoorState, KnowledgeBase
from amiro.behavior.planning.planner import HomePlanner
from amiro.behavior.planning.problem import Goal, RobotState
from amiro.behavior.planning.topology import topology_from_world
from amiro.core.config import ConfigError
from amiro.home.world import World, default_home_path

DOCK = RobotState("hallway", 0.8, 1.0)
GOAL = [Goal("notified", "maria")]


@pytest.fixture
def kb() -> KnowledgeBase:
    topo = topology_from_world(World.load(default_home_path()))
    return KnowledgeBase(topo, {"maria": "living_room", "john": "hallway"})


def actions(kb: KnowledgeBase, engine: str = "kairos") -> list[str]:
    outcome = HomePlanner(PlanningConfig(engine=engine)).plan(kb, DOCK, GOAL)
    assert outcome.solved, outcome.explanation
    return [str(s) for s in outcome.steps]


def test_valid_plan_through_the_direct_door(kb: KnowledgeBase) -> None:
    assert actions(kb) == [
        "move(robot_start, living_door_hallway)",
        "cross(living_door, living_door_hallway, living_door_living_room)",
        "approach(maria, living_door_living_room)",
        "deliver(maria)",
    ]


def test_closed_door_and_a_helper_nearby_means_asking_for_help(kb: KnowledgeBase) -> None:
    kb.set_door("living_door", DoorState.CLOSED, 1.0, "lidar")
    steps = actions(kb)
    assert "ask_open_door(john, living_door, living_door_hallway)" in steps
    assert steps.index("ask_open_door(john, living_door, living_door_hallway)") < steps.index(
        "cross(living_door, living_door_hallway, living_door_living_room)"
    )


def test_helper_declined_means_the_way_through_the_kitchen(kb: KnowledgeBase) -> None:
    kb.set_door("living_door", DoorState.CLOSED, 1.0, "lidar")
    kb.declined("john", 2.0)
    crossed = [s.split("(")[1].split(",")[0] for s in actions(kb) if s.startswith("cross")]
    assert crossed == ["kitchen_door", "kitchen_living_door"]


def test_no_plan_fails_cleanly_with_an_explanation(kb: KnowledgeBase) -> None:
    kb.set_door("living_door", DoorState.LOCKED, 1.0, "test")
    kb.set_door("kitchen_living_door", DoorState.CLOSED, 1.0, "lidar")
    kb.declined("john", 2.0)
    outcome = HomePlanner().plan(kb, DOCK, GOAL)
    assert not outcome.solved and outcome.steps == []
    assert "maria is in living_room" in outcome.explanation
    assert "living_door is locked" in outcome.explanation
    assert "kitchen_living_door is closed" in outcome.explanation


def test_unknown_whereabouts_lead_to_search_and_then_an_explanation(kb: KnowledgeBase) -> None:
    kb.person_not_found("maria", "living_room", 1.0)
    steps = actions(kb)
    assert any(s.startswith("search(maria") for s in steps)
    for room in kb.topology.rooms:
        kb.person_not_found("maria", room, 2.0)
    outcome = HomePlanner().plan(kb, DOCK, GOAL)
    assert not outcome.solved and "nobody knows where maria is" in outcome.explanation


def test_temporal_plan_with_kairos_has_durations_from_distances(kb: KnowledgeBase) -> None:
    planner = HomePlanner(PlanningConfig(engine="kairos", temporal=True))
    outcome = planner.plan(kb, DOCK, GOAL)
    assert outcome.solved
    first = outcome.steps[0]
    assert first.action == "move" and first.args[0] == "robot_start"
    wp = kb.topology.waypoints[first.args[1]]
    distance = ((wp.x - DOCK.x) ** 2 + (wp.y - DOCK.y) ** 2) ** 0.5
    assert first.duration_s == pytest.approx(distance / 0.35, abs=0.1)
    assert [s.action for s in outcome.steps][-1] == "deliver"


@pytest.mark.parametrize("engine", ["pyperplan", "fast-downward"])
def test_gpl_engines_chosen_in_config_plan_as_the_default(kb: KnowledgeBase, engine: str) -> None:
    assert actions(kb, engine) == actions(kb)


def test_temporal_needs_a_temporal_engine() -> None:
    with pytest.raises(ValueError, match="kairos"):
        PlanningConfig(engine="pyperplan", temporal=True)
    with pytest.raises(ConfigError, match="unknown door"):
        KnowledgeBase(topology_from_world(World.load(default_home_path()))).set_door(
            "garage", DoorState.OPEN, 0.0, "test"
        )
