"""The dashboard's robot in the cloud process: bridged topics in, behaviour goals out.

:class:`RemoteRobot` implements :class:`~amiro.web.robot.RobotPort` from what crosses to
the cloud: the pose estimate (the topic navigation publishes, as ``/amcl_pose`` would),
the people the edge tracks (``/amiro/people``), the behaviour events of ``/amiro/events``
(running task and queue), and the dashboard's one-task behaviours go to the edge as
``/amiro/behavior/run`` goals.
"""

from __future__ import annotations

from typing import Any

from amiro.behavior.task import make_task
from amiro.core import names
from amiro.core.messages import BehaviorEvent, People, Pose2D
from amiro.core.node import Node
from amiro.deploy.behaviors import BehaviorGoal, BehaviorRequests
from amiro.deploy.people import dashboard_people
from amiro.home.world import HomeSpec
from amiro.web.robot import pose_dict


class RemoteRobot(Node):
    def __init__(
        self,
        home: HomeSpec,
        scenarios: dict[str, int],
        pose_topic: str,
        requests: BehaviorRequests,
    ) -> None:
        super().__init__("remote_robot")
        self._home = home
        self._scenarios = dict(sorted(scenarios.items()))
        self.pose_topic = pose_topic
        self.requests = requests
        self.pose: Pose2D | None = None
        self.people: People | None = None
        self.current: dict[str, Any] | None = None
        self.queued: dict[str, dict[str, Any]] = {}

    def on_start(self) -> None:
        self.create_subscription(self.pose_topic, Pose2D, self._on_pose, 1)
        self.create_subscription(names.PEOPLE, People, self._on_people, 1)
        self.create_subscription(names.EVENTS, BehaviorEvent, self._on_event, 1000)

    @property
    def home(self) -> HomeSpec:
        return self._home

    def scenarios(self) -> dict[str, int]:
        return dict(self._scenarios)

    def state(self) -> dict[str, Any]:
        return {
            "robot": pose_dict(self.pose) if self.pose is not None else None,
            "people": dashboard_people(self.people),
            "current": self.current,
            "queue": [q for q in self.queued.values() if q["graph"] != self._current_graph()],
            "doors": {d.name: d.open for d in self._home.doors},  # as configured: no live view
        }

    def run_task(self, task_type: str, params: dict[str, Any], priority: int) -> str:
        make_task(task_type, params)  # wrong type or parameters: TaskError here, not remotely
        goal = BehaviorGoal(task_type, dict(params), priority, single_task=True)
        return self.requests.request(goal).id

    def _current_graph(self) -> str | None:
        return None if self.current is None else self.current["graph"]

    def _on_pose(self, pose: Pose2D) -> None:
        self.pose = pose

    def _on_people(self, people: People) -> None:
        self.people = people

    def _on_event(self, ev: BehaviorEvent) -> None:
        if ev.graph is None:
            return
        if ev.type == "graph_submitted":
            detail = ev.detail
            self.queued[ev.graph] = {
                "graph": ev.graph,
                "name": detail.get("name", ev.graph),
                "task": detail.get("entry", ""),
                "type": "",
                "priority": detail.get("priority", 0),
            }
        elif ev.type == "task_started":
            queued = self.queued.get(ev.graph, {})
            self.current = {
                "graph": ev.graph,
                "name": queued.get("name", ev.graph),
                "priority": queued.get("priority", 0),
                "task": ev.task,
                "type": ev.detail.get("task_type", ""),
                "started_s": round(ev.stamp, 3),
            }
        elif ev.type == "graph_finished":
            self.queued.pop(ev.graph, None)
            if self._current_graph() == ev.graph:
                self.current = None
