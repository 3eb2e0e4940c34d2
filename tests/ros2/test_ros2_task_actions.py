"""Search and RecognizeActivity as real ROS 2 actions (``amiro_interfaces``): a plain rclpy
client (tests/ros2/scripts/send_goal.py, what ``ros2 action send_goal`` does) calls the
edge's RecognizeActivity, which runs the task on the behaviour engine."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import amiro.behavior.tasks  # noqa: F401 - registers the task types
from amiro.activity.ports import ActivityReading
from amiro.behavior.engine import BehaviorEngine
from amiro.behavior.modules import Modules
from amiro.core import names
from amiro.core.bus import GoalStatus
from amiro.core.clock import SimClock
from amiro.core.messages import Point
from amiro.core.runtime import Runtime
from amiro.deploy.codecs import SearchCodec
from amiro.deploy.task_actions import (
    RecognizeActivityAction,
    SearchFeedback,
    SearchGoal,
    SearchResult,
    TaskActionServer,
)
from amiro.ros2.actions import ActionExporter
from amiro.ros2.bridge import Ros2Bridge
from amiro.ros2.context import RosContext
from amiro.ros2.env import ros_environment

SEND_GOAL = Path(__file__).parent / "scripts" / "send_goal.py"
SUCCEEDED, ABORTED = 4, 6  # action_msgs/GoalStatus


class ScriptedActivity:
    """A stand-in recogniser (an oracle for the test): typing twice, then drinking."""

    def __init__(self) -> None:
        self.looks = 0

    def observe(self, person: str) -> ActivityReading:
        self.looks += 1
        label = "typing" if self.looks <= 2 else "drink_water"
        return ActivityReading(label, 0.9, True)


def _send_goal(runtime: Runtime, domain_id: int, goal: dict[str, Any]) -> dict[str, Any]:
    """Runs the plain client while this process's runtime serves it."""
    proc = subprocess.Popen(
        [
            sys.executable,
            str(SEND_GOAL),
            names.RECOGNIZE_ACTIVITY,
            "amiro_interfaces/action/RecognizeActivity",
            json.dumps(goal),
        ],
        env={**os.environ, **ros_environment(domain_id)},
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    deadline = time.monotonic() + 180.0
    while proc.poll() is None and time.monotonic() < deadline:
        runtime.spin_for(0.05)
    out, err = proc.communicate(timeout=30)
    assert proc.returncode == 0, err
    return dict(json.loads(out.strip().splitlines()[-1]))


def test_a_plain_client_runs_recognize_activity_on_the_engine(domain_id: int) -> None:
    ros = RosContext("amiro_test_edge", domain_id)
    runtime = Runtime(SimClock(speed=1.0))
    activity = ScriptedActivity()
    runtime.add(Ros2Bridge(ros))
    engine = runtime.add(BehaviorEngine(modules=Modules(activity=activity)))  # type: ignore[arg-type]
    runtime.add(TaskActionServer(engine, RecognizeActivityAction()))
    exporter = runtime.add(ActionExporter(ros, known_codec()))
    runtime.start()
    try:
        seen = _send_goal(runtime, domain_id, {"person": "anna", "activity": "drink_water"})
        missed = _send_goal(
            runtime, domain_id, {"person": "anna", "activity": "walk", "timeout_s": 2.0}
        )
        # 3 sightings cannot come out of the last 2 readings
        impossible = _send_goal(runtime, domain_id, {"person": "anna", "of_last": 2})
    finally:
        runtime.stop()
        ros.close()
    assert seen["accepted"] and seen["status"] == SUCCEEDED
    assert seen["result"] == {"recognised": True, "outcome": "recognised"}
    feedback = [(f["current"], f["confirmations"]) for f in seen["feedback"]]
    # ("", 0) first when the engine's poll comes before the task's first look
    assert ("typing", 0) in feedback and ("drink_water", 2) in feedback
    assert feedback.index(("typing", 0)) < feedback.index(("drink_water", 2))
    assert missed["accepted"] and missed["status"] == ABORTED
    assert missed["result"] == {"recognised": False, "outcome": "not_recognised"}
    assert impossible["status"] == ABORTED and impossible["feedback"] == []
    assert impossible["result"] == {"recognised": False, "outcome": "rejected"}
    assert [r.type for r in engine.records] == ["RecognizeActivity", "RecognizeActivity"]
    assert exporter.active == {} and exporter.stats.errors == 0


def known_codec() -> Any:
    from amiro.deploy.interfaces import known_action

    codec = known_action(names.RECOGNIZE_ACTIVITY)
    assert codec.ros_type == "amiro_interfaces/action/RecognizeActivity"
    return codec


def test_search_travels_field_for_field() -> None:
    codec = SearchCodec()
    goal = SearchGoal("anna", dwell_s=0.8, sightings=3, side_steps=1)
    assert codec.goal_from_ros(codec.goal_to_ros(goal)) == goal
    feedback = SearchFeedback("kitchen", "head")
    assert codec.feedback_from_ros(codec.feedback_to_ros(feedback, 1.0)) == feedback
    found = SearchResult(True, "found", Point(1.5, -2.0, 1.2), "kitchen")
    assert (
        codec.result_from_ros(
            codec.result_to_ros(found, GoalStatus.SUCCEEDED), GoalStatus.SUCCEEDED
        )
        == found
    )
    lost = SearchResult(False, "not_found")
    assert (
        codec.result_from_ros(codec.result_to_ros(lost, GoalStatus.ABORTED), GoalStatus.ABORTED)
        == lost
    )
