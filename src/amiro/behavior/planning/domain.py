"""The PDDL domain of a home, built with unified-planning (section 3.7's future work).

Types: ``waypoint``, ``room``, ``door``, ``person``.  The robot moves between waypoints of a
room, crosses open doors, asks a person in its room to open a closed (not locked) door or to
clear an obstacle, searches for a person whose room is unknown, approaches a person, delivers a
notification and checks an activity.  Approaching keeps the robot's waypoint: the next move
starts from there, which is where the dispatcher sends it.  Facts about the home's shape are
static (pyperplan's grounding prunes on them); people do not move during a plan, so "person p
can be met from waypoint w" is static too.  The temporal variant makes every action durative,
moves and crossings lasting their distance over the robot's speed.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

from unified_planning.model import (
    DurativeAction,
    EndTiming,
    Fluent,
    InstantaneousAction,
    StartTiming,
)
from unified_planning.model.action import Action
from unified_planning.model.fnode import FNode
from unified_planning.model.types import Type
from unified_planning.shortcuts import BoolType, RealType, UserType

from amiro.behavior.planning.environment import planning_environment

# Fixed durations (s) of the actions that do not travel, for temporal planning.
DURATIONS_S = {
    "ask_open_door": 15.0,
    "ask_clear": 20.0,
    "search": 40.0,
    "approach": 10.0,
    "deliver": 10.0,
    "check_activity": 30.0,
}


@dataclass(frozen=True)
class HomeDomain:
    """The types, fluents and actions; a problem adds a home's objects and facts."""

    temporal: bool
    waypoint: Type
    room: Type
    door: Type
    person: Type
    fluents: dict[str, Fluent]
    static: frozenset[str]
    actions: tuple[Action, ...]

    def fluent(self, name: str) -> Fluent:
        return self.fluents[name]


@cache
def home_domain(temporal: bool = False) -> HomeDomain:
    """Built once per variant: problems share the same fluent and action objects."""
    planning_environment()  # UP's environment made before anything of UP is
    wp, room, door, person = (UserType(n) for n in ("waypoint", "room", "door", "person"))
    b = BoolType()
    f = {
        "robot_at": Fluent("robot_at", b, w=wp),
        "robot_near": Fluent("robot_near", b, p=person),
        "in_room": Fluent("in_room", b, w=wp, r=room),
        "link": Fluent("link", b, a=wp, b=wp),
        "door_side": Fluent("door_side", b, d=door, w=wp),
        "opposite": Fluent("opposite", b, a=wp, b=wp),
        "door_open": Fluent("door_open", b, d=door),
        "door_closed": Fluent("door_closed", b, d=door),
        "door_locked": Fluent("door_locked", b, d=door),
        "clear": Fluent("clear", b, w=wp),
        "person_by": Fluent("person_by", b, p=person, w=wp),
        "maybe_by": Fluent("maybe_by", b, p=person, w=wp),
        "willing": Fluent("willing", b, p=person),
        "notified": Fluent("notified", b, p=person),
        "activity_checked": Fluent("activity_checked", b, p=person),
    }
    if temporal:
        f["travel_time"] = Fluent("travel_time", RealType(), a=wp, b=wp)
    static = frozenset(
        {"in_room", "link", "door_side", "opposite", "person_by", "maybe_by", "travel_time"}
    )
    builder = _ActionBuilder(temporal)

    a = builder.new("move", {"a": wp, "b": wp})
    x, y = a.parameter("a"), a.parameter("b")
    builder.pre(a, f["robot_at"](x), f["link"](x, y), f["clear"](y))
    builder.eff(a, (f["robot_at"](x), False), (f["robot_at"](y), True))
    builder.duration(a, f["travel_time"](x, y) if temporal else None)

    a = builder.new("cross", {"d": door, "a": wp, "b": wp})
    d, x, y = a.parameter("d"), a.parameter("a"), a.parameter("b")
    builder.pre(a, f["robot_at"](x), f["door_side"](d, x), f["opposite"](x, y), f["door_open"](d))
    builder.eff(a, (f["robot_at"](x), False), (f["robot_at"](y), True))
    builder.duration(a, f["travel_time"](x, y) if temporal else None)

    a = builder.new("ask_open_door", {"p": person, "d": door, "w": wp})
    p, d, x = (a.parameter(n) for n in ("p", "d", "w"))
    builder.pre(
        a,
        f["robot_at"](x),
        f["door_side"](d, x),
        f["person_by"](p, x),
        f["willing"](p),
        f["door_closed"](d),
    )
    builder.eff(a, (f["door_closed"](d), False), (f["door_open"](d), True))

    a = builder.new("ask_clear", {"p": person, "a": wp, "b": wp})
    p, x, y = (a.parameter(n) for n in ("p", "a", "b"))
    builder.pre(a, f["robot_at"](x), f["link"](x, y), f["person_by"](p, x), f["willing"](p))
    builder.eff(a, (f["clear"](y), True))

    for name, where in (("approach", "person_by"), ("search", "maybe_by")):
        a = builder.new(name, {"p": person, "w": wp})
        p, w = a.parameter("p"), a.parameter("w")
        builder.pre(a, f["robot_at"](w), f[where](p, w))
        builder.eff(a, (f["robot_near"](p), True))

    for name, goal in (("deliver", "notified"), ("check_activity", "activity_checked")):
        a = builder.new(name, {"p": person})
        p = a.parameter("p")
        builder.pre(a, f["robot_near"](p))
        builder.eff(a, (f[goal](p), True))

    return HomeDomain(temporal, wp, room, door, person, f, static, tuple(builder.actions))


class _ActionBuilder:
    """Writes each action once for both variants: conditions at start, effects at the end
    (and the robot leaves its waypoint at the start)."""

    def __init__(self, temporal: bool) -> None:
        self.temporal = temporal
        self.actions: list[Action] = []

    def new(self, name: str, params: dict[str, Type]) -> Action:
        action: Action = (
            DurativeAction(name, params) if self.temporal else InstantaneousAction(name, params)
        )
        if isinstance(action, DurativeAction) and name in DURATIONS_S:
            action.set_fixed_duration(DURATIONS_S[name])
        self.actions.append(action)
        return action

    def pre(self, action: Action, *conditions: FNode) -> None:
        for c in conditions:
            if isinstance(action, DurativeAction):
                action.add_condition(StartTiming(), c)
            else:
                assert isinstance(action, InstantaneousAction)
                action.add_precondition(c)

    def eff(self, action: Action, *effects: tuple[FNode, bool]) -> None:
        for fluent, value in effects:
            if isinstance(action, DurativeAction):
                timing = StartTiming() if not value else EndTiming()
                action.add_effect(timing, fluent, value)
            else:
                assert isinstance(action, InstantaneousAction)
                action.add_effect(fluent, value)

    def duration(self, action: Action, expr: FNode | None) -> None:
        if isinstance(action, DurativeAction) and expr is not None:
            action.set_fixed_duration(expr)
