"""The problem generator: a home's objects and the knowledge base's facts as a PDDL problem."""

from __future__ import annotations

import math
from dataclasses import dataclass

from unified_planning.model import Object, Problem
from unified_planning.shortcuts import Fraction

from amiro.behavior.planning.domain import HomeDomain
from amiro.behavior.planning.knowledge import DoorState, KnowledgeBase
from amiro.core.config import ConfigError

START = "robot_start"  # the waypoint added where the robot stands when planning begins
GOAL_KINDS = ("notified", "activity_checked")


@dataclass(frozen=True, slots=True)
class Goal:
    kind: str  # "notified" or "activity_checked"
    person: str


@dataclass(frozen=True, slots=True)
class RobotState:
    """Where the robot stands: a room and a map position."""

    room: str
    x: float
    y: float


def make_problem(
    domain: HomeDomain,
    kb: KnowledgeBase,
    robot: RobotState,
    goals: list[Goal],
    speed_mps: float = 0.35,
) -> Problem:
    topo = kb.topology
    if robot.room not in topo.rooms:
        raise ConfigError(f"the robot is outside every room of {topo.name} (in {robot.room!r})")
    for g in goals:
        if g.kind not in GOAL_KINDS:
            raise ConfigError(f"unknown goal {g.kind!r} (choices: {', '.join(GOAL_KINDS)})")
    f = domain.fluent
    problem = Problem(f"{topo.name}_task")
    for fluent in domain.fluents.values():
        default = 0 if fluent.type.is_real_type() else False
        problem.add_fluent(fluent, default_initial_value=default)
    problem.add_actions(domain.actions)

    rooms = {r: Object(r, domain.room) for r in topo.rooms}
    spots = {w: Object(w, domain.waypoint) for w in topo.waypoints}
    spots[START] = Object(START, domain.waypoint)
    doors = {d: Object(d, domain.door) for d in topo.doors}
    people = {p: Object(p, domain.person) for p in {*kb.people, *(g.person for g in goals)}}
    for objs in (rooms, spots, doors, people):
        problem.add_objects(objs.values())

    room_of = {w: wp.room for w, wp in topo.waypoints.items()} | {START: robot.room}
    xy = {w: (wp.x, wp.y) for w, wp in topo.waypoints.items()} | {START: (robot.x, robot.y)}
    by_room: dict[str, list[str]] = {}
    for w, r in room_of.items():
        problem.set_initial_value(f("in_room")(spots[w], rooms[r]), True)
        by_room.setdefault(r, []).append(w)
        if w not in kb.blocked:
            problem.set_initial_value(f("clear")(spots[w]), True)
    for names in by_room.values():
        for a in names:
            for b in names:
                if a != b:
                    problem.set_initial_value(f("link")(spots[a], spots[b]), True)
                    _set_time(problem, domain, spots[a], spots[b], xy[a], xy[b], speed_mps)
    for name, door in topo.doors.items():
        x, y = door.sides
        for a, b in ((x, y), (y, x)):
            problem.set_initial_value(f("door_side")(doors[name], spots[a]), True)
            problem.set_initial_value(f("opposite")(spots[a], spots[b]), True)
            _set_time(problem, domain, spots[a], spots[b], xy[a], xy[b], speed_mps)
        state = kb.doors[name]
        key = {DoorState.OPEN: "door_open", DoorState.CLOSED: "door_closed"}.get(state)
        problem.set_initial_value(f(key or "door_locked")(doors[name]), True)

    for name, obj in people.items():
        belief = kb.person(name)
        if belief.willing:
            problem.set_initial_value(f("willing")(obj), True)
        where = "person_by" if belief.room is not None else "maybe_by"
        for room in kb.candidate_rooms(name):
            for w in by_room.get(room, []):
                problem.set_initial_value(f(where)(obj, spots[w]), True)
    problem.set_initial_value(f("robot_at")(spots[START]), True)
    for g in goals:
        problem.add_goal(f(g.kind)(people[g.person]))
    return problem


def _set_time(
    problem: Problem,
    domain: HomeDomain,
    a: Object,
    b: Object,
    pa: tuple[float, float],
    pb: tuple[float, float],
    speed: float,
) -> None:
    if domain.temporal:
        seconds = max(math.hypot(pa[0] - pb[0], pa[1] - pb[1]) / speed, 0.1)
        value = Fraction(round(seconds * 10), 10)
        problem.set_initial_value(domain.fluent("travel_time")(a, b), value)
