"""The robot as the dashboard sees it, wherever it runs.

The dashboard needs little of the robot: the home's map, the behaviours it knows, a view of
its state (pose, people, running task, queue) and a way to start a one-task behaviour.
:class:`RobotPort` is that narrow interface: :class:`SystemRobot` implements it on the
embedded system's objects, and the cloud process of a split deployment implements it on
bridged topics (:mod:`amiro.deploy.web_robot`), so the same app serves both.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Protocol

from amiro.behavior.engine import GraphRun
from amiro.behavior.graph import End, TaskGraph
from amiro.behavior.handlers import HandlerError
from amiro.behavior.task import TaskError, make_task
from amiro.core.messages import Pose2D
from amiro.home.world import HomeSpec

if TYPE_CHECKING:
    from amiro.system import System


class RobotPort(Protocol):
    @property
    def home(self) -> HomeSpec:
        """The home's rooms, walls, doors and furniture, drawn as the map."""
        ...

    def scenarios(self) -> dict[str, int]:
        """The behaviour kinds a notification can start, each with its own priority (a fall
        is raised at the fall behaviour's priority, so it preempts a hydration reminder)."""
        ...

    def state(self) -> dict[str, Any]:
        """``robot`` pose, ``people`` seen, ``current`` task (with ``progress`` when known),
        ``queue`` and ``doors`` open or closed (runtime thread)."""
        ...

    def run_task(self, task_type: str, params: dict[str, Any], priority: int) -> str:
        """Start a one-task behaviour (runtime thread); its id.  Raises TaskError when the
        task type or its parameters are wrong."""
        ...


def single_task_graph(task_type: str, params: dict[str, Any], priority: int) -> TaskGraph:
    """The behaviour the dashboard's task form runs: one task, nothing after it."""
    task = make_task(task_type, params)
    return TaskGraph(f"web_{task_type.lower()}", priority).add("task", task)


DEFAULT_PRIORITY = 5  # a behaviour kind whose graph cannot be built without a payload


def progress(run: GraphRun, task_id: str) -> dict[str, Any]:
    """A run's steps for a progress bar: the tasks done (with their result), the one running,
    and the ones that follow it if each succeeds (the graph's success path)."""
    done = [{"task": r.task_id, "type": r.type, "result": r.result} for r in run.records]
    ahead: list[dict[str, Any]] = []
    edge = run.graph.tasks[task_id].on_success
    seen = {task_id}
    while not isinstance(edge, End) and edge not in seen:
        seen.add(edge)
        node = run.graph.tasks[edge]
        ahead.append({"task": node.id, "type": node.type_name})
        edge = node.on_success
    return {"done": done, "ahead": ahead}


def pose_dict(pose: Pose2D) -> dict[str, float]:
    return {"x": round(pose.x, 3), "y": round(pose.y, 3), "theta": round(pose.theta, 3)}


class SystemRobot:
    """The embedded system: the robot's pose and the people in the home (the simulator's
    truth, or a real robot's estimates), the engine itself."""

    def __init__(self, system: System) -> None:
        self.system = system

    @property
    def home(self) -> HomeSpec:
        return self.system.world.home

    def scenarios(self) -> dict[str, int]:
        handlers, out = self.system.handlers, {}
        for kind in handlers.kinds():
            try:
                out[kind] = handlers.build(kind).priority
            except (HandlerError, TaskError, ValueError):
                out[kind] = DEFAULT_PRIORITY
        return out

    def state(self) -> dict[str, Any]:
        engine, pose = self.system.engine, self.system.robot_pose()
        current = engine.current()
        if current is not None:
            current["progress"] = progress(engine.runs[current["graph"]], current["task"])
        return {
            "robot": pose_dict(pose) if pose is not None else None,
            "people": [
                {"name": p.name, "x": round(p.x, 2), "y": round(p.y, 2), "activity": p.activity}
                for p in self.system.people()
            ],
            "current": current,
            "queue": engine.queue_snapshot(),
            "doors": dict(self.system.world.doors),
        }

    def run_task(self, task_type: str, params: dict[str, Any], priority: int) -> str:
        graph = single_task_graph(task_type, params, priority)
        return self.system.engine.submit(graph).id
