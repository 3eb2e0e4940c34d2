"""The whole system on a ROS 2 robot (``robot.adapter: ros2``), the robot being
``amiro node sim`` in another process with its rendered camera: AMCL localises on the
robot's /scan and /odom, a ``go_to`` behaviour drives it over /cmd_vel to a named place, and
HOG on the camera's pixels places the resident standing in front of it."""

from __future__ import annotations

import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import yaml

from amiro.core.clock import WallClock
from amiro.perception.onnx_standins import fixed_answer_model
from amiro.ros2.env import ros_environment
from amiro.system import SystemConfig, build_system
from sim_driver import stop_sim

MARIA = (6.0, 4.2)  # standing in the hallway, 4 m ahead of the robot parked at "hallway"
HALLWAY = (2.0, 4.2)
RESIDENTS = [{"name": "maria", "pose": {"x": MARIA[0], "y": MARIA[1], "theta": math.pi}}]


def start_sim(tmp_path: Path, domain: int) -> subprocess.Popen[str]:
    (tmp_path / "home.yaml").write_text(yaml.safe_dump({"sim": {"residents": RESIDENTS}}))
    node = {
        "role": "sim",
        "scenario": None,
        "system": str(tmp_path / "home.yaml"),
        "camera": {"rate_hz": 2.0, "width": 320, "height": 240},
        "duration_s": 120.0,
    }
    (tmp_path / "sim.yaml").write_text(yaml.safe_dump(node))
    command = [sys.executable, "-m", "amiro.cli", "node", "sim"]
    command += ["--config", str(tmp_path / "sim.yaml"), "--report", str(tmp_path / "sim.json")]
    env = {**os.environ, **ros_environment(domain)}
    return subprocess.Popen(
        command, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )


def robot_config(tmp_path: Path, domain: int) -> SystemConfig:
    # No pose model ships: one that never sees anyone stands in for the user's.
    pose = fixed_answer_model(tmp_path / "pose.onnx", np.zeros((1, 56)), channels_first=True)
    return SystemConfig.model_validate(
        {
            "robot": {"adapter": "ros2", "profile": "amiro_sim", "ros": {"domain_id": domain}},
            "perception": {"backend": "camera", "camera": {"detector": "hog"}},
            "activity": {"backend": "camera-onnx", "pose": {"model": pose}},
            "sim": {"residents": RESIDENTS},  # the household's names and languages
        }
    )


def test_whole_system_drives_and_sees_through_the_robots_topics(
    robot_domain: int, tmp_path: Path
) -> None:
    sim = start_sim(tmp_path, robot_domain)
    system = build_system(robot_config(tmp_path, robot_domain), WallClock())
    assert system.sim is None and system.robot is not None
    placed: list[tuple[float, float]] = []
    try:
        system.start()
        robot = system.robot
        assert system.runtime.spin_until(lambda: robot.stats()["scans"] > 5, 30.0)
        run = system.engine.submit(system.handlers.build("go_to", {"room_entity": "hallway"}))
        assert system.runtime.spin_until(lambda: run.done, 40.0)
        assert run.outcome == "completed"

        def seen() -> bool:
            found = system.camera_people.look() if system.camera_people else []
            placed.extend((p.position.x, p.position.y) for p in found)
            return bool(found)

        assert system.runtime.spin_until(seen, 10.0)
        estimate = system.navigation.pose
        stats = robot.stats()
    finally:
        system.stop()
        report = stop_sim(sim, tmp_path)
    x, y, _ = report["pose"]
    assert math.dist((x, y), HALLWAY) < 0.35  # the simulator's own pose: it got there
    assert estimate is not None and math.dist((estimate.x, estimate.y), (x, y)) < 0.3  # AMCL
    assert stats["images"] > 0 and stats["commands"] > 0 and stats["errors"] == 0
    assert math.dist(placed[-1], MARIA) < 0.5  # HOG + depth + estimator, 4 m away
