"""The split deployment on a real ROS 2 robot: ``amiro sim --ros2`` (paced at real time,
camera on) stands in for the robot's driver; the edge (``robot.adapter: ros2``, camera
perception) and the cloud run on wall time as separate processes under :class:`Launcher`;
a ``go_to`` asked over ``/amiro/behavior/run`` drives the robot to a named place."""

from __future__ import annotations

import math
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml

from amiro.core import names
from amiro.core.clock import WallClock
from amiro.core.config import ConfigError, parse
from amiro.core.runtime import Runtime
from amiro.deploy.behaviors import BehaviorGoal
from amiro.deploy.config import NodeConfig
from amiro.deploy.interfaces import known_action
from amiro.deploy.launch import Launcher, load_deployment
from amiro.perception.onnx_standins import fixed_answer_model
from amiro.ros2.actions import RemoteActionServer
from amiro.ros2.bridge import Ros2Bridge
from amiro.ros2.context import RosContext
from amiro.ros2.env import ros_environment
from sim_driver import stop_sim

HALLWAY = (2.0, 4.2)  # the named place the robot is sent to (the shipped apartment's)


def _write(path: Path, data: dict[str, Any]) -> Path:
    path.write_text(yaml.safe_dump(data), encoding="utf-8")
    return path


def _robot_system(tmp_path: Path) -> Path:
    # No pose model ships: one that never sees anyone stands in for the user's.
    pose = fixed_answer_model(tmp_path / "pose.onnx", np.zeros((1, 56)), channels_first=True)
    system = {
        "robot": {"adapter": "ros2", "profile": "amiro_sim"},
        "perception": {"backend": "camera", "camera": {"detector": "hog"}},
        "activity": {"backend": "camera-onnx", "pose": {"model": str(pose)}},
    }
    return _write(tmp_path / "robot-system.yaml", system)


def _deployment(tmp_path: Path) -> Path:
    system = str(_robot_system(tmp_path))
    common = {"clock": "wall", "scenario": None, "system": system}
    edge = {"role": "edge", **common, "serve_actions": [names.BEHAVIOR_RUN], "heartbeat_s": 0.5}
    cloud = {"role": "cloud", **common, "watch": {"edge": 3.0}}
    processes = [
        {"name": name, "config": str(_write(tmp_path / f"{name}.yaml", cfg)), "restart": "never"}
        for name, cfg in (("edge", edge), ("cloud", cloud))
    ]
    return _write(tmp_path / "robot.yaml", {"name": "robot", "processes": processes})


def _start_driver(tmp_path: Path, domain: int) -> subprocess.Popen[str]:
    command = [sys.executable, "-m", "amiro.cli", "sim", "--ros2", "--speed", "1"]
    command += ["--camera-rate", "2", "--report", str(tmp_path / "sim.json")]
    env = {**os.environ, **ros_environment(domain)}
    return subprocess.Popen(
        command, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )


def _ask_go_to(domain: int, place: str) -> Any:
    """What the cloud's dialogue or dashboard would do: ask the edge for ``go_to``."""
    runtime = Runtime(WallClock())
    ros = RosContext("amiro_test_client", domain)
    runtime.add(Ros2Bridge(ros))  # an empty bridge only pumps ROS 2
    scans: list[object] = []
    ros.subscribe("sensor_msgs/msg/LaserScan", "/scan", scans.append, depth=1)
    remote = runtime.add(RemoteActionServer(ros, known_action(names.BEHAVIOR_RUN), timeout_s=10.0))
    try:
        runtime.start()
        assert runtime.spin_until(lambda: remote.server_heard is not None, 60.0)
        # The edge is up: give its localisation a few seconds of the robot's scans (a goal
        # arriving before AMCL's first pose fails with no_pose).
        scans.clear()
        assert runtime.spin_until(lambda: len(scans) >= 40, 30.0)
        handle = runtime.bus.send_goal(
            names.BEHAVIOR_RUN, BehaviorGoal("go_to", {"room_entity": place})
        )
        assert runtime.spin_until(lambda: handle.done, 60.0)
        return handle.result
    finally:
        runtime.stop()
        ros.close()


@pytest.mark.slow
def test_edge_and_cloud_drive_a_ros2_robot_on_wall_time(tmp_path: Path, domain_id: int) -> None:
    sim = _start_driver(tmp_path, domain_id)
    launcher = Launcher(
        load_deployment(_deployment(tmp_path)), tmp_path / "logs", domain_id=domain_id
    )
    try:
        launcher.start()
        result = _ask_go_to(domain_id, "hallway")
    finally:
        launcher.stop()
        driver = stop_sim(sim, tmp_path)
    assert launcher.unclean_exits() == {}
    assert result.ok and result.outcome == "completed"
    x, y, _ = driver["pose"]
    assert math.dist((x, y), HALLWAY) < 0.35  # the robot's own pose: it got there
    edge = launcher.report("edge")
    assert edge["runs"][-1]["outcome"] == "completed"
    robot = edge["robot"]
    assert robot["scans"] > 10 and robot["odom"] > 10 and robot["images"] > 0
    assert robot["commands"] > 0 and robot["errors"] == 0
    assert edge["bridge"]["errors"] == 0
    assert math.dist(edge["pose_estimate"][:2], (x, y)) < 0.3  # AMCL on the robot's topics
    cloud = launcher.report("cloud")
    assert cloud["lost"] == {"edge": 0}  # the cloud heard the edge's heartbeat throughout


def test_the_sim_role_refuses_wall_time() -> None:
    with pytest.raises(ConfigError, match="owns simulated time"):
        parse(NodeConfig, {"role": "sim", "clock": "wall"}, "sim.yaml")
