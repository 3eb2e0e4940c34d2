"""From a plan to a behaviour: one task per plan action, in one task graph.

Each task's id names its action (``a2_cross``), so the executive reading the engine's events
knows which action succeeded or failed.  Composite actions use :class:`Sequence` of the
paper's tasks: crossing a door is a lidar check then a MoveTo to the far side; asking for
help is a Say, a Listen and a wait for the door to be seen open.  Requests are phrases of
``phrases.yaml`` in the behaviour's language (blackboard ``lang``), and the phrase key is the
dialogue act, so a listener (a resident of the simulator) knows what it is asked.
"""

from __future__ import annotations

import math
from typing import Any

import amiro.behavior.planning.tasks  # noqa: F401 - registers Sequence and CheckDoor
from amiro.behavior.graph import End, TaskGraph
from amiro.behavior.planning.planner import PlanStep
from amiro.behavior.planning.problem import START, RobotState
from amiro.behavior.planning.topology import Topology
from amiro.behavior.task import Task, make_task
from amiro.dialogue.phrases import phrase

OPEN_DOOR_REQUEST = "open_door_request"  # phrase key and dialogue act
CLEAR_REQUEST = "clear_request"

STEP_FAILED = End("step_failed")
APPROACH_M = 1.2


def task_id(index: int, step: PlanStep) -> str:
    return f"a{index}_{step.action}"


def step_index(task: str) -> int | None:
    head = task.split("_", 1)[0]
    return int(head[1:]) if head.startswith("a") and head[1:].isdigit() else None


def _spec(type_name: str, **params: Any) -> dict[str, Any]:
    return {"type": type_name, "params": params}


class _Positions:
    def __init__(self, topology: Topology, robot: RobotState) -> None:
        self.xy = {w: (p.x, p.y) for w, p in topology.waypoints.items()}
        self.xy[START] = (robot.x, robot.y)

    def pose(self, src: str, dst: str) -> dict[str, float]:
        """The waypoint ``dst`` facing away from ``src`` (the way the robot travels)."""
        (x0, y0), (x1, y1) = self.xy[src], self.xy[dst]
        return {"x": x1, "y": y1, "theta": math.atan2(y1 - y0, x1 - x0)}


def _request(key: str, person: str, lang: str) -> dict[str, Any]:
    """Say the request ``key`` to ``person`` (ids are lower-case names)."""
    text = phrase(key, lang, {"name": person.title()})
    return _spec("Say", text=text, act=key, to=person, lang=lang)


def _task_for(step: PlanStep, where: _Positions, lang: str) -> Task:
    a = step.args
    if step.action == "move":
        return make_task("MoveTo", {"target": where.pose(a[0], a[1])})
    if step.action == "cross":
        door, src, dst = a
        return make_task(
            "Sequence",
            {
                "steps": [
                    _spec("CheckDoor", door=door, timeout_s=1.0),
                    _spec("MoveTo", target=where.pose(src, dst)),
                ]
            },
        )
    if step.action in ("ask_open_door", "ask_clear"):
        opening = step.action == "ask_open_door"
        steps = [
            _request(OPEN_DOOR_REQUEST if opening else CLEAR_REQUEST, a[0], lang),
            _spec("Listen", expect=["affirm"], timeout_s=10.0),
        ]
        if step.action == "ask_open_door":
            steps.append(_spec("CheckDoor", door=a[1], wait_open=True, timeout_s=20.0))
        else:
            steps.append(_spec("Wait", seconds=10.0))
        return make_task("Sequence", {"steps": steps})
    if step.action in ("approach", "search"):
        return make_task(
            "Sequence",
            {
                "steps": [
                    _spec("Search", person=a[0]),
                    _spec("MoveTo", target="$person_position", approach=APPROACH_M),
                ]
            },
        )
    if step.action == "deliver":
        return make_task("Say", {"text": "$message", "act": "notification", "to": a[0]})
    if step.action == "check_activity":
        return make_task(
            "RecognizeActivity",
            {"person": a[0], "activity": "$activity", "look_at": "$person_position"},
        )
    raise ValueError(f"no task for plan action {step.action}")


def plan_graph(
    steps: list[PlanStep],
    topology: Topology,
    robot: RobotState,
    name: str,
    priority: int,
    blackboard: dict[str, Any],
) -> TaskGraph:
    """The behaviour that executes ``steps`` in order (temporal plans by start time)."""
    ordered = sorted(steps, key=lambda s: s.start_s or 0.0)
    where = _Positions(topology, robot)
    lang = str(blackboard.get("lang", "en"))
    graph = TaskGraph(name, priority, blackboard=blackboard)
    ids = [task_id(i, s) for i, s in enumerate(ordered)]
    for i, step in enumerate(ordered):
        nxt = ids[i + 1] if i + 1 < len(ids) else End("completed")
        graph.add(ids[i], _task_for(step, where, lang), on_success=nxt, on_failure=STEP_FAILED)
    return graph
