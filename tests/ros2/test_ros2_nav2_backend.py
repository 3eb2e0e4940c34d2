"""``navigation.backend: nav2``: MoveTo as a client of a robot's own Nav2, here a stand-in
Nav2 written in plain rclpy (tests/ros2/scripts/nav2_standin.py)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
import yaml

import amiro.behavior.tasks  # noqa: F401 - registers MoveTo
from amiro.behavior.engine import BehaviorEngine, EngineConfig
from amiro.behavior.graph import End, TaskGraph
from amiro.behavior.task import make_task
from amiro.core import names
from amiro.core.bus import GoalStatus
from amiro.core.clock import SimClock
from amiro.core.config import ConfigError
from amiro.core.messages import Pose2D
from amiro.core.runtime import Runtime
from amiro.deploy.cloud import pose_topic
from amiro.deploy.codecs import MoveToCodec, NavigateToPoseCodec, nav2_reason
from amiro.deploy.config import DEFAULT_PUBLISH, DEFAULT_SUBSCRIBE
from amiro.deploy.launch import Launcher, load_deployment
from amiro.deploy.nav2 import Nav2Primitives, add_nav2_navigation
from amiro.home.world import World, default_home_path
from amiro.navigation.config import NavigationConfig
from amiro.navigation.move_to import MoveToFeedback
from amiro.navigation.primitives import ForwardGoal, RotateGoal
from amiro.navigation.stack import build_navigation
from amiro.ros2.actions import RemoteActionServer
from amiro.ros2.bridge import Ros2Bridge
from amiro.ros2.context import RosContext
from amiro.ros2.env import ros_environment
from amiro.system import SystemConfig

STANDIN = Path(__file__).parent / "scripts" / "nav2_standin.py"


def _standin(mode: str, domain_id: int) -> subprocess.Popen[str]:
    return subprocess.Popen(
        [sys.executable, str(STANDIN), mode],
        env={**os.environ, **ros_environment(domain_id)},
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


def _stop(proc: subprocess.Popen[str]) -> dict[str, int]:
    proc.send_signal(signal.SIGTERM)
    out, err = proc.communicate(timeout=30)
    assert proc.returncode == 0, err
    return dict(json.loads(out.strip().splitlines()[-1]))


def test_nav2_result_codes_map_to_move_to_reasons() -> None:
    assert nav2_reason(208, "") == "unreachable"  # ComputePathToPose NO_VALID_PATH
    assert nav2_reason(105, "") == "stuck"  # FollowPath FAILED_TO_MAKE_PROGRESS
    assert nav2_reason(202, "") == "no_pose"  # TF_ERROR
    assert nav2_reason(9001, "bt") == "nav2_error_9001: bt"
    assert nav2_reason(714, "") == "blocked"  # BackUp COLLISION_AHEAD
    assert nav2_reason(701, "") == "timeout"  # Spin TIMEOUT
    with pytest.raises(ConfigError, match="backend: nav2"):
        build_navigation(None, {}, NavigationConfig(backend="nav2"))  # type: ignore[arg-type]


def test_move_tos_recoveries_are_nav2s_number_of_recoveries() -> None:
    feedback = MoveToFeedback(Pose2D(1.0, 2.0, 0.5), 3.25, recoveries=2)
    codec = NavigateToPoseCodec()
    msg = codec.feedback_to_ros(feedback, elapsed_s=4.5)
    assert msg.number_of_recoveries == 2 and msg.distance_remaining == 3.25
    assert (msg.navigation_time.sec, msg.navigation_time.nanosec) == (4, 500_000_000)
    back = codec.feedback_from_ros(msg)
    assert back.recoveries == 2 and back.pose.x == 1.0 and abs(back.pose.theta - 0.5) < 1e-9
    ours = MoveToCodec()
    assert ours.feedback_from_ros(ours.feedback_to_ros(feedback, 0.0)) == feedback


def test_an_aborted_nav2_goal_takes_move_tos_failure_edge(domain_id: int) -> None:
    standin = _standin("abort", domain_id)
    ros = RosContext("amiro_test_edge", domain_id)
    runtime = Runtime(SimClock(speed=1.0))
    world = World.load(default_home_path(), 0.05)
    places = {name: world.place(name) for name in world.home.places}
    runtime.add(Ros2Bridge(ros))
    runtime.add(RemoteActionServer(ros, NavigateToPoseCodec(places), timeout_s=60.0))
    engine = runtime.add(BehaviorEngine(config=EngineConfig()))
    runtime.start()
    try:
        graph = TaskGraph("go_kitchen", 1).add(
            "go",
            make_task("MoveTo", {"target": "kitchen"}),
            on_failure=End("could_not_get_there"),
        )
        run = engine.submit(graph)
        deadline = time.monotonic() + 120.0
        while run.outcome is None and time.monotonic() < deadline:
            runtime.spin_for(0.05)
    finally:
        runtime.stop()
        ros.close()
        counts = _stop(standin)
    assert run.outcome == "could_not_get_there"
    (record,) = [r for r in engine.records if r.task_id == "go"]
    assert record.result == "failure" and record.detail["reason"] == "unreachable"
    assert counts == {
        "goals": 1,
        "succeeded": 0,
        "aborted": 1,
        "canceled": 0,
        "behaviors": {"backup": 0, "drive_on_heading": 0, "succeeded": 0},
    }


def test_primitives_use_nav2s_behaviour_server_where_the_robot_offers_it(domain_id: int) -> None:
    """The stand-in offers /backup and /drive_on_heading (aborting: COLLISION_AHEAD) but no
    /spin: forward and back go to the behaviour server, a turn falls back on
    /navigate_to_pose (aborting: NO_VALID_PATH); each ends with the reason Nav2's code means."""
    standin = _standin("abort", domain_id)
    ros = RosContext("amiro_test_edge", domain_id)
    runtime = Runtime(SimClock(speed=1.0))
    cfg = SystemConfig(navigation=NavigationConfig(backend="nav2"))
    runtime.add(Ros2Bridge(ros))
    remotes = add_nav2_navigation(
        runtime, ros, cfg, World.load(default_home_path(), 0.05), timeout_s=60.0
    )
    runtime.start()
    runtime.bus.publish(pose_topic(cfg), Pose2D(1.0, 2.0, 0.0))  # where the turn starts
    try:
        assert ros.wait_for_nodes(["nav2_standin"], 60.0) == []
        backup, drive = remotes[2], remotes[3]
        primitives = runtime.nodes["nav2_primitives"]
        assert isinstance(primitives, Nav2Primitives)
        ready = lambda: backup.available and drive.available and primitives.navigation.pose  # noqa: E731
        deadline = time.monotonic() + 60.0
        while not ready() and time.monotonic() < deadline:
            runtime.spin_for(0.05)
        goals = [
            (names.FORWARD, ForwardGoal(-0.3)),
            (names.FORWARD, ForwardGoal(0.3, 0.1)),
            (names.ROTATE, RotateGoal(1.0)),
        ]
        handles = [runtime.bus.send_goal(action, goal) for action, goal in goals]
        deadline = time.monotonic() + 120.0
        while not all(h.done for h in handles) and time.monotonic() < deadline:
            runtime.spin_for(0.05)
    finally:
        runtime.stop()
        ros.close()
        counts = _stop(standin)
    assert [h.status for h in handles] == [GoalStatus.ABORTED] * 3
    assert [h.result.reason for h in handles] == ["blocked", "blocked", "unreachable"]
    assert primitives.routes == {"/backup": 1, "/drive_on_heading": 1, "/navigate_to_pose": 1}
    assert counts["behaviors"] == {"backup": 1, "drive_on_heading": 1, "succeeded": 0}
    assert counts["goals"] == 1  # the turn, as a pose goal


def _write(path: Path, data: dict[str, object]) -> Path:
    path.write_text(yaml.safe_dump(data), encoding="utf-8")
    return path


@pytest.mark.slow
def test_hydration_completes_with_move_to_on_nav2(tmp_path: Path, domain_id: int) -> None:
    """The robot process runs its own navigation behind the stand-in Nav2 (as a Nav2 robot
    would); the edge's MoveTo only speaks NavigateToPose to /navigate_to_pose."""
    sim = {
        "role": "sim",
        "speed": 3.0,
        "wait_for": ["amiro_edge", "amiro_cloud", "nav2_standin"],
        "serve_actions": [names.MOVE_TO, names.FORWARD],  # what the stand-in Nav2 relays to
        "publish": [*DEFAULT_PUBLISH["sim"], names.LOCALIZATION],
        "subscribe": ["/amiro/head/cmd", "/amiro/say"],
    }
    system = _write(tmp_path / "edge-system.yaml", {"navigation": {"backend": "nav2"}})
    edge = {
        "role": "edge",
        "heartbeat_s": 0.5,
        "system": str(system),
        "action_timeout_s": 30.0,
        "publish": [t for t in DEFAULT_PUBLISH["edge"] if t != "/cmd_vel"],
        "subscribe": [
            *(t for t in DEFAULT_SUBSCRIBE["edge"] if t != "/scan"),
            "/odom",
            names.LOCALIZATION,
        ],
    }
    cloud = {"role": "cloud", "watch": {"edge": 2.0, "sim": 2.0}, "stop_after_acks": 1}
    processes = [
        {"name": n, "config": str(_write(tmp_path / f"{n}.yaml", c)), "restart": "never"}
        for n, c in (("sim", sim), ("edge", edge))
    ]
    processes.append(
        {
            "name": "cloud",
            "config": str(_write(tmp_path / "cloud.yaml", cloud)),
            "restart": "never",
            "ends_deployment": True,
        }
    )
    deployment = _write(
        tmp_path / "nav2.yaml", {"name": "nav2", "timeout_s": 300, "processes": processes}
    )
    standin = _standin("relay", domain_id)
    try:
        launcher = Launcher(load_deployment(deployment), tmp_path / "logs", domain_id=domain_id)
        outcome = launcher.run_all()
    finally:
        counts = _stop(standin)
    assert outcome == "cloud finished"
    edge_report = launcher.report("edge")
    called = edge_report["actions"]["ros2_call:/navigate_to_pose"]
    assert called["sent"] >= 1 and called["errors"] == 0
    # the drinking seen after the approach Nav2 drove, and the reframing before watching
    # through Nav2's behaviour server (BackUp / DriveOnHeading relayed to the robot)
    assert [run["outcome"] for run in edge_report["runs"]] == ["completed"]
    assert launcher.report("cloud")["outcome"] == "acknowledged"
    assert counts["goals"] >= 1 and counts["succeeded"] >= 1
    reframed = counts["behaviors"]  # (cancelled by the edge once the framing is right)
    assert reframed["backup"] + reframed["drive_on_heading"] >= 1
    assert not launcher.unclean_exits(), launcher.unclean_exits()
