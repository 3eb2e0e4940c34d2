"""Plans and why there is no plan, in words a carer can act on.

The planner only says "unsolvable"; this walks the rooms the robot believes it can reach
(through open doors, and closed ones when someone willing to open them is on its side) and
names what stands between the robot and each goal: a door closed or locked, nobody to help,
a person nobody knows where to find.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from amiro.behavior.planning.knowledge import DoorState, KnowledgeBase
from amiro.behavior.planning.problem import Goal, RobotState

if TYPE_CHECKING:
    from amiro.behavior.planning.planner import PlanStep  # planner imports this module

_WORDS = {
    "move": "go to {1}",
    "cross": "go through {0}",
    "ask_open_door": "ask {P} to open {1}",
    "ask_clear": "ask {P} to clear the way to {2}",
    "search": "look for {P} at {1}",
    "approach": "go to {P}",
    "deliver": "tell {P}",
    "check_activity": "check what {P} is doing",
}


def describe_step(step: PlanStep) -> str:
    """``ask_open_door(john, living_door, ...)`` → ``ask John to open living_door``."""
    template = _WORDS.get(step.action)
    if template is None:
        return str(step)
    return template.format(*step.args, P=step.args[0].title() if step.args else "")


def describe_plan(steps: list[PlanStep]) -> str:
    """The plan in words, moves inside a room left out: they only lead to the next action."""
    return " → ".join(describe_step(s) for s in steps if s.action != "move") or "nothing to do"


def reachable_rooms(kb: KnowledgeBase, start: str) -> set[str]:
    helpers = {b.room for b in kb.people.values() if b.willing and b.room is not None}
    seen = {start}
    todo = [start]
    while todo:
        room = todo.pop()
        for name, door in kb.topology.doors.items():
            if room not in door.rooms:
                continue
            other = door.rooms[1 - door.rooms.index(room)]
            state = kb.doors[name]
            passable = state is DoorState.OPEN or (state is DoorState.CLOSED and room in helpers)
            if passable and other not in seen:
                seen.add(other)
                todo.append(other)
    return seen


def _blocking_doors(kb: KnowledgeBase, reached: set[str]) -> list[str]:
    out = []
    for name, door in kb.topology.doors.items():
        inside = [r in reached for r in door.rooms]
        if any(inside) and not all(inside):
            state = kb.doors[name]
            why = "nobody willing to open it is on this side" if state is DoorState.CLOSED else ""
            out.append(f"{name} is {state}" + (f" ({why})" if why else ""))
    return out


def explain_no_plan(kb: KnowledgeBase, robot: RobotState, goals: list[Goal]) -> str:
    reached = reachable_rooms(kb, robot.room)
    reasons = []
    for goal in goals:
        rooms = kb.candidate_rooms(goal.person)
        if not rooms:
            searched = ", ".join(sorted(kb.person(goal.person).not_in))
            reasons.append(f"nobody knows where {goal.person} is (searched: {searched})")
            continue
        if any(r in reached for r in rooms):
            continue
        where = rooms[0] if len(rooms) == 1 else f"any of {', '.join(rooms)}"
        blocking = "; ".join(_blocking_doors(kb, reached)) or "no door leads there"
        reasons.append(
            f"{goal.person} is in {where}, which the robot cannot reach from the "
            f"{robot.room}: {blocking}"
        )
    if not reasons:
        blocked = ", ".join(sorted(kb.blocked))
        return f"no plan found (blocked waypoints: {blocked or 'none'})"
    return "; ".join(reasons)
