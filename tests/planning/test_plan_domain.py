"""The PDDL domain and problem generated from the home."""

from __future__ import annotations

import numpy as np
import pytest
from unified_planning.io import PDDLWriter

from amiro.behavior.planning.domain import home_domain
from amiro.behavior.planning.knowledge import DoorState, KnowledgeBase
from amiro.behavior.planning.problem import Goal, RobotState, make_problem
from amiro.behavior.planning.topology import grid_topology, topology_from_world
from amiro.core.config import ConfigError
from amiro.home.world import World, default_home_path


@pytest.fixture(scope="module")
def world() -> World:
    return World.load(default_home_path())


def test_topology_has_a_free_waypoint_on_each_side_of_every_door(world: World) -> None:
    topo = topology_from_world(world)
    assert set(topo.rooms) == {"hallway", "living_room", "kitchen", "bedroom", "bathroom"}
    assert set(topo.doors) == set(world.doors)
    for door in topo.doors.values():
        for room, side in zip(door.rooms, door.sides, strict=True):
            wp = topo.waypoints[side]
            assert world.room_at(wp.x, wp.y) == room
            assert world.is_free(wp.x, wp.y, 0.35)


def test_domain_has_the_issues_actions_and_durations() -> None:
    names = {a.name for a in home_domain(False).actions}
    assert names == {
        "move",
        "cross",
        "ask_open_door",
        "ask_clear",
        "approach",
        "search",
        "deliver",
        "check_activity",
    }
    temporal = home_domain(True)
    assert "travel_time" in temporal.fluents
    assert all(type(a).__name__ == "DurativeAction" for a in temporal.actions)


def test_problem_pddl_names_rooms_doors_people_and_door_states(world: World) -> None:
    kb = KnowledgeBase(topology_from_world(world), {"maria": "living_room"})
    kb.set_door("kitchen_door", DoorState.LOCKED, 0.0, "test")
    problem = make_problem(
        home_domain(False), kb, RobotState("hallway", 0.8, 1.0), [Goal("notified", "maria")]
    )
    writer = PDDLWriter(problem)
    domain, task = writer.get_domain(), writer.get_problem()
    assert "(:action cross" in domain and "(:action ask_open_door" in domain
    for kind, name in (("door", "living_door"), ("person", "maria"), ("room", "kitchen")):
        declared = next(line for line in task.splitlines() if line.strip().endswith(f"- {kind}"))
        assert name in declared.split()
    assert "(door_locked kitchen_door)" in task
    assert "(door_open living_door)" in task
    assert "(notified maria)" in task


def test_problem_rejects_a_robot_outside_the_home(world: World) -> None:
    kb = KnowledgeBase(topology_from_world(world))
    with pytest.raises(ConfigError, match="outside every room"):
        make_problem(home_domain(False), kb, RobotState("garden", 0, 0), [])


def test_generated_homes_connect_every_room() -> None:
    topo = grid_topology(10, np.random.default_rng(3))
    assert len(topo.rooms) == 10
    reached, todo = {topo.rooms[0]}, [topo.rooms[0]]
    while todo:
        room = todo.pop()
        for door in topo.doors.values():
            if room in door.rooms:
                other = door.rooms[1 - door.rooms.index(room)]
                if other not in reached:
                    reached.add(other)
                    todo.append(other)
    assert reached == set(topo.rooms)
    assert len(topo.doors) >= 9
