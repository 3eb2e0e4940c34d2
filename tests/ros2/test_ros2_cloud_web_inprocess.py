"""The cloud's dashboard and dialogue without ROS: the cloud role and a behaviour server
share one bus, so what crosses to the edge in a deployment is checked here in one process."""

from __future__ import annotations

import time
from collections.abc import Iterator
from dataclasses import dataclass
from importlib import resources
from typing import Any

import httpx
import pytest
from pydantic import SecretStr

from amiro.behavior.engine import BehaviorEngine
from amiro.behavior.graph import TaskGraph
from amiro.behavior.handlers import HandlerRegistry
from amiro.behavior.task import make_task
from amiro.core import names
from amiro.core.clock import SimClock
from amiro.core.config import ConfigError, load
from amiro.core.messages import Pose2D, SpeechHeard, SpeechRequest
from amiro.core.runtime import Runtime
from amiro.deploy.behaviors import BehaviorActionServer, BehaviorGoal, BehaviorRequests
from amiro.deploy.config import DEFAULT_PUBLISH, DEFAULT_SUBSCRIBE, NodeConfig
from amiro.deploy.dialogue import DialogueBehaviors
from amiro.deploy.process import system_config
from amiro.deploy.roles import build_cloud_role
from amiro.dialogue.config import DialogueConfig
from amiro.dialogue.stack import build_dialogue
from amiro.web.config import WebConfig
from amiro.web.served import RuntimeLoop

PASSWORD = "cloud dashboard password"


def _wait_graph(payload: dict[str, Any]) -> TaskGraph:
    """A stand-in go_to: waits as long as the payload says, then ends."""
    seconds = float(payload.get("seconds", 0.5))
    return TaskGraph("go_to", 3).add("wait", make_task("Wait", {"seconds": seconds}))


def _edge(runtime: Runtime) -> BehaviorActionServer:
    engine = runtime.add(BehaviorEngine())
    handlers = HandlerRegistry(engine)
    handlers.register("go_to", _wait_graph)
    return runtime.add(BehaviorActionServer(engine, handlers))


def _said(runtime: Runtime) -> list[SpeechRequest]:
    said: list[SpeechRequest] = []
    runtime.bus.subscribe(names.SAY, SpeechRequest, said.append, depth=100)
    return said


def test_a_requested_behaviour_runs_and_its_end_comes_back() -> None:
    runtime = Runtime(SimClock())
    server = _edge(runtime)
    client = runtime.add(BehaviorRequests())
    runtime.start()
    req = client.request(BehaviorGoal("go_to", {"seconds": 2.0}))
    runtime.spin_for(1.0)
    assert req.ended_s is None and req.run == "go_to#1"  # running: feedback named the run
    runtime.spin_for(2.0)
    assert (req.outcome, req.ok) == ("completed", True)
    assert (req.ended_s or 0.0) >= 2.0
    assert [r.run for r in server.finished] == ["go_to#1"]


def test_an_unknown_behaviour_is_rejected_with_the_reason() -> None:
    runtime = Runtime(SimClock())
    _edge(runtime)
    client = runtime.add(BehaviorRequests())
    runtime.start()
    req = client.request(BehaviorGoal("dance", {}))
    assert req.ok is False and req.outcome is not None
    assert req.outcome.startswith("rejected") and "dance" in req.outcome


def test_a_one_task_goal_and_a_cancelled_one() -> None:
    runtime = Runtime(SimClock())
    _edge(runtime)
    client = runtime.add(BehaviorRequests())
    runtime.start()
    req = client.request(BehaviorGoal("Wait", {"seconds": 30.0}, 7, single_task=True))
    runtime.spin_for(0.5)
    assert req.run == "web_wait#1" and req.outcome is None
    handle = runtime.bus.send_goal(names.BEHAVIOR_RUN, BehaviorGoal("go_to", {"seconds": 30.0}))
    runtime.spin_for(0.5)
    handle.cancel()
    runtime.spin_for(0.5)
    assert handle.status.value == "canceled"
    assert handle.result is not None and handle.result.outcome == "cancelled"


def test_a_spoken_command_becomes_a_goal_and_the_robot_says_how_it_ended() -> None:
    runtime = Runtime(SimClock())
    _edge(runtime)
    requests = runtime.add(BehaviorRequests())
    said = _said(runtime)
    behaviors = DialogueBehaviors(requests, runtime.bus.publisher(names.SAY, SpeechRequest))
    dialogue = build_dialogue(runtime, DialogueConfig(), submit=behaviors)
    runtime.start()
    answer = dialogue.manager.handle("go to the kitchen", "en", "maria")
    assert answer.action == "go_to" and answer.entities["room_entity"] == "kitchen"
    assert [r.goal.payload["room_entity"] for r in requests.requests] == ["kitchen"]
    assert requests.requests[0].goal.payload["requested_by"] == "maria"
    runtime.spin_for(2.0)
    assert [s.text for s in said if s.act == "behavior_outcome"] == ["I have arrived: kitchen."]
    assert behaviors.answers[0]["outcome"] == "completed"


def test_without_an_edge_the_dialogue_says_it_cannot_go() -> None:
    runtime = Runtime(SimClock())
    requests = runtime.add(BehaviorRequests())
    said = _said(runtime)
    behaviors = DialogueBehaviors(requests, runtime.bus.publisher(names.SAY, SpeechRequest))
    runtime.start()
    assert behaviors("go_to", {"room_entity": "bedroom", "lang": "fr"}) is None
    runtime.spin_for(0.1)
    assert [s.text for s in said] == ["Je n'ai pas pu aller à bedroom (no_edge)."]


def test_the_dashboard_needs_the_behaviour_action() -> None:
    runtime = Runtime(SimClock())
    node = NodeConfig(role="cloud", web=WebConfig(port=0, admin_password=SecretStr("x")))
    with pytest.raises(ConfigError, match="call_actions"):
        build_cloud_role(runtime, "cloud", node, system_config(node, 1))


@dataclass
class Cloud:
    runtime: Runtime
    url: str
    report: Any


@pytest.fixture
def cloud() -> Iterator[Cloud]:
    runtime = Runtime(SimClock(speed=20.0))
    web = WebConfig(port=0, admin_password=SecretStr(PASSWORD))
    node = NodeConfig(role="cloud", web=web, call_actions=(names.BEHAVIOR_RUN,))
    parts = build_cloud_role(runtime, "cloud", node, system_config(node, 1))
    _edge(runtime)  # the edge's behaviour server, on the same bus here
    runtime.start()
    loop = RuntimeLoop(runtime)
    loop.start()
    try:
        yield Cloud(runtime, parts.summary()["web"], parts.summary)
    finally:
        loop.stop()
        runtime.stop()


def _login(client: httpx.Client) -> None:
    res = client.post("/auth/login", json={"user": "admin", "password": PASSWORD})
    assert res.status_code == 200
    client.headers["X-CSRF-Token"] = res.json()["csrf"]


def test_the_cloud_dashboard_shows_the_bridged_pose_and_runs_commands(cloud: Cloud) -> None:
    with httpx.Client(base_url=cloud.url, timeout=10) as client:
        assert client.get("/api/state").status_code == 401
        _login(client)
        assert client.get("/api/state").json()["robot"] is None  # no estimate yet
        pose = Pose2D(1.5, 2.0, 0.5)
        cloud.runtime.bus.publish(names.LOCALIZATION, pose)  # as the bridge would
        assert _poll(client, lambda s: s["robot"] == {"x": 1.5, "y": 2.0, "theta": 0.5})
        home = client.get("/api/map").json()
        assert "kitchen" in home["rooms"] and home["walls"]
        assert "go_to" in client.get("/api/behaviours").json()["scenarios"]
        bad = client.post("/api/tasks", json={"type": "Fly", "params": {}})
        assert bad.status_code == 422 and "Fly" in bad.json()["detail"]
        res = client.post("/api/tasks", json={"type": "Wait", "params": {"seconds": 5}})
        assert res.status_code == 200 and res.json()["run"] == "request-1"
        assert _poll(client, lambda s: (s["current"] or {}).get("graph") == "web_wait#1")
        reply = client.post("/api/chat", json={"text": "go to the kitchen", "user": "maria"})
        assert reply.json()["reply"] == "I am going to kitchen."
        assert _poll(
            client,
            lambda s: any(m["text"] == "I have arrived: kitchen." for m in s["transcript"]),
            timeout_s=20,
        )
    requests = cloud.report()["behavior_requests"]
    assert [r["kind"] for r in requests] == ["Wait", "go_to"]
    assert all(r["outcome"] == "completed" for r in requests)


def _poll(client: httpx.Client, pred: Any, timeout_s: float = 10.0) -> bool:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if pred(client.get("/api/state").json()):
            return True
        time.sleep(0.05)
    return False


def test_a_command_heard_by_the_robot_reaches_the_behaviour_layer(cloud: Cloud) -> None:
    heard = SpeechHeard(text="go to the bedroom", lang="en", speaker="maria")
    cloud.runtime.bus.publish(names.HEARD, heard)  # as the bridge would, from the robot
    requests = _until_value(lambda: cloud.report().get("behavior_requests"))
    assert [(r["kind"], r["run"]) for r in requests] == [("go_to", "go_to#1")]
    outcomes = _until_value(lambda: cloud.report().get("dialogue_outcomes"))
    assert [o["text"] for o in outcomes] == ["I have arrived: bedroom."]


def _until_value(get: Any, timeout_s: float = 10.0) -> Any:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        value = get()
        if value and all(r.get("outcome") for r in value):
            return value
        time.sleep(0.05)
    return get()


def test_the_web_deployment_adds_its_topics_to_the_role_defaults() -> None:
    deployments = resources.files("amiro").joinpath("data/deployments")
    edge = load(NodeConfig, str(deployments.joinpath("hydration-web-edge.yaml")))
    cloud = load(NodeConfig, str(deployments.joinpath("hydration-web-cloud.yaml")))
    assert edge.topics_out() == (*DEFAULT_PUBLISH["edge"], names.LOCALIZATION)
    assert edge.topics_in() == DEFAULT_SUBSCRIBE["edge"]
    assert cloud.topics_in()[: len(DEFAULT_SUBSCRIBE["cloud"])] == DEFAULT_SUBSCRIBE["cloud"]
    assert {names.SAY, names.HEARD, names.LOCALIZATION} <= set(cloud.topics_in())
    assert cloud.web is not None and names.BEHAVIOR_RUN in cloud.call_actions
    assert names.BEHAVIOR_RUN in edge.serve_actions
