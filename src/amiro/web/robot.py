"""The robot as the dashboard sees it, wherever it runs.

The dashboard needs little of the robot: the home's map, the behaviours it knows, a view of
its state (pose, people, running task, queue) and a way to start a one-task behaviour.
:class:`RobotPort` is that narrow interface: :class:`SystemRobot` implements it on the
embedded system's objects, and the cloud process of a split deployment implements it on
bridged topics (:mod:`amiro.deploy.web_robot`), so the same app serves both.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Protocol

from amiro.behavior.graph import TaskGraph
from amiro.behavior.task import make_task
from amiro.core.messages import Pose2D
from amiro.home.world import HomeSpec

if TYPE_CHECKING:
    from amiro.system import System


class RobotPort(Protocol):
    @property
    def home(self) -> HomeSpec:
        """The home's rooms, walls, doors and furniture, drawn as the map."""
        ...

    def scenarios(self) -> list[str]:
        """The behaviour kinds a notification can start."""
        ...

    def state(self) -> dict[str, Any]:
        """``robot`` pose, ``people`` seen, ``current`` task and ``queue`` (runtime thread)."""
        ...

    def run_task(self, task_type: str, params: dict[str, Any], priority: int) -> str:
        """Start a one-task behaviour (runtime thread); its id.  Raises TaskError when the
        task type or its parameters are wrong."""
        ...


def single_task_graph(task_type: str, params: dict[str, Any], priority: int) -> TaskGraph:
    """The behaviour the dashboard's task form runs: one task, nothing after it."""
    task = make_task(task_type, params)
    return TaskGraph(f"web_{task_type.lower()}", priority).add("task", task)


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

    def scenarios(self) -> list[str]:
        return self.system.handlers.kinds()

    def state(self) -> dict[str, Any]:
        engine, pose = self.system.engine, self.system.robot_pose()
        return {
            "robot": pose_dict(pose) if pose is not None else None,
            "people": [
                {"name": p.name, "x": round(p.x, 2), "y": round(p.y, 2), "activity": p.activity}
                for p in self.system.people()
            ],
            "current": engine.current(),
            "queue": engine.queue_snapshot(),
        }

    def run_task(self, task_type: str, params: dict[str, Any], priority: int) -> str:
        graph = single_task_graph(task_type, params, priority)
        return self.system.engine.submit(graph).id
