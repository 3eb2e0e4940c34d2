"""Why there is no plan, in words a carer can act on.

The planner only says "unsolvable"; this walks the rooms the robot believes it can reach
(through open doors, and closed ones when someone willing to open them is on its side) and
names what stands between the robot and each goal: a door closed or locked, nobody to help,
a person nobody knows where to find.
"""

from __future__ import annotations

from amiro.behavior.planning.knowledge import DoorState, KnowledgeBase
from amiro.behavior.planning.problem import Goal, RobotState


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
