"""The dashboard in the cloud process of a three-process deployment (sim, edge, cloud over
ROS 2 on loopback): an HTTP client logs in, sees the robot's pose, the people the edge
tracks and behaviour events update, and its commands (the task form, a typed "go to the
kitchen") run on the edge."""

from __future__ import annotations

import socket
import time
from collections.abc import Callable
from importlib import resources
from pathlib import Path
from typing import Any

import httpx
import pytest
import yaml

from amiro.deploy.launch import Launcher, load_deployment
from amiro.home.world import World, default_home_path

DEPLOYMENTS = Path(str(resources.files("amiro").joinpath("data/deployments")))
PASSWORD = "web in the cloud"
State = dict[str, Any]


def _free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def _deployment(tmp_path: Path, port: int) -> Path:
    """hydration-web.yaml without the heat wave (nothing but our commands moves the robot),
    time at twice real time, the dashboard on a free port with a known password."""
    sim = yaml.safe_load((DEPLOYMENTS / "hydration-sim.yaml").read_text())
    sim["speed"] = 2.0  # the edge keeps pace on a busy 2-core machine
    (tmp_path / "sim.yaml").write_text(yaml.safe_dump(sim))
    quiet = tmp_path / "quiet.yaml"
    quiet.write_text(yaml.safe_dump({"environment": {"sensors": {"changes": []}}}))
    cloud = yaml.safe_load((DEPLOYMENTS / "hydration-web-cloud.yaml").read_text())
    cloud["web"] = {"port": port, "admin_password": PASSWORD}
    cloud["system"] = str(quiet)
    (tmp_path / "cloud.yaml").write_text(yaml.safe_dump(cloud))
    deployment = yaml.safe_load((DEPLOYMENTS / "hydration-web.yaml").read_text())
    configs = {
        "sim": tmp_path / "sim.yaml",
        "edge": DEPLOYMENTS / "hydration-web-edge.yaml",
        "cloud": tmp_path / "cloud.yaml",
    }
    for process in deployment["processes"]:
        process["config"] = str(configs[process["name"]])
    path = tmp_path / "deployment.yaml"
    path.write_text(yaml.safe_dump(deployment))
    return path


def _until(pred: Callable[[], Any], timeout_s: float) -> Any:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        try:
            found = pred()
        except httpx.TransportError:
            found = None
        if found:
            return found
        time.sleep(0.1)
    return None


def _finished(state: State, graph: str) -> str | None:
    for event in state["events"]:
        if event["type"] == "graph_finished" and event.get("graph") == graph:
            return str(event["outcome"])
    return None


@pytest.mark.slow
def test_the_cloud_dashboard_drives_the_edge(tmp_path: Path, domain_id: int) -> None:
    port = _free_port()
    launcher = Launcher(load_deployment(_deployment(tmp_path, port)), tmp_path, domain_id=domain_id)
    launcher.start()
    client = httpx.Client(base_url=f"http://127.0.0.1:{port}", timeout=15)
    try:
        assert _until(lambda: client.get("/healthz").status_code == 200, 60), "no dashboard"
        assert client.get("/api/state").status_code == 401
        login = client.post("/auth/login", json={"user": "admin", "password": PASSWORD})
        assert login.status_code == 200
        client.headers["x-csrf-token"] = login.json()["csrf"]

        def state() -> State:
            return dict(client.get("/api/state").json())

        start = _until(lambda: state().get("robot"), 60)
        assert start, "the edge's pose estimate never reached the cloud"

        # The task form: the robot drives to the living room; the pose and events follow.
        sent = time.monotonic()
        res = client.post(
            "/api/tasks", json={"type": "MoveTo", "params": {"target": "living_room"}}
        )
        assert res.status_code == 200 and res.json()["run"] == "request-1"
        current = _until(lambda: state()["current"], 30)
        latency_s = time.monotonic() - sent
        assert current and (current["graph"], current["type"]) == ("web_moveto#1", "MoveTo")
        print(f"web command -> edge task started: {latency_s * 1000:.0f} ms wall")
        assert _until(lambda: _finished(state(), "web_moveto#1"), 120) == "completed"
        in_living_room = state()["robot"]

        # The edge's perception finds Maria; the dashboard shows her where it tracks her.
        res = client.post("/api/tasks", json={"type": "Search", "params": {"person": "maria"}})
        assert res.status_code == 200
        maria = _until(lambda: [p for p in state()["people"] if p["name"] == "maria"], 120)
        assert _until(lambda: _finished(state(), "web_search#1"), 120) == "completed"

        # A typed command in the cloud's chat: the edge runs go_to, the outcome comes back.
        reply = client.post("/api/chat", json={"text": "go to the kitchen", "user": "maria"})
        assert reply.json()["reply"] == "I am going to kitchen."
        assert _until(lambda: _finished(state(), "go_to#1"), 120) == "completed"
        said = "I have arrived: kitchen."
        assert _until(lambda: any(m["text"] == said for m in state()["transcript"]), 10)
        final = state()["robot"]
    finally:
        client.close()
        launcher.stop()

    world = World.load(default_home_path())
    assert world.room_at(start["x"], start["y"]) == "hallway"
    assert world.room_at(in_living_room["x"], in_living_room["y"]) == "living_room"
    assert world.room_at(final["x"], final["y"]) == "kitchen"
    assert maria and set(maria[0]) == {"name", "x", "y", "activity"}
    assert world.room_at(maria[0]["x"], maria[0]["y"]) is not None  # a place in the home
    sim = launcher.report("sim")
    assert world.room_at(sim["pose"][0], sim["pose"][1]) == "kitchen"  # the robot itself
    cloud = launcher.report("cloud")
    requests = {r["kind"]: r for r in cloud["behavior_requests"]}
    assert requests["MoveTo"]["outcome"] == "completed"
    assert requests["go_to"]["outcome"] == "completed" and requests["go_to"]["run"] == "go_to#1"
    assert [a["text"] for a in cloud["dialogue_outcomes"]] == [said]
    edge = launcher.report("edge")
    assert [r["id"] for r in edge["runs"]] == ["web_moveto#1", "web_search#1", "go_to#1"]
    assert all(r["outcome"] == "completed" for r in edge["runs"])
    # The cloud (dashboard, dialogue) stops cleanly; the edge's exit is the deployment tests'.
    assert "cloud" not in launcher.unclean_exits(), launcher.unclean_exits()
