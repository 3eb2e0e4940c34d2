"""``amiro sim --ros2 --navigation`` as a Nav2 server: a plain rclpy Nav2 client that knows
nothing of amiro drives the simulated robot through /navigate_to_pose."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from amiro.home.world import World, default_home_path
from amiro.ros2.env import ros_environment

SCRIPT = Path(__file__).parent / "scripts" / "nav2_client.py"


@pytest.mark.slow
def test_a_plain_nav2_client_drives_amiro_and_cancels_it(domain_id: int) -> None:
    world = World.load(default_home_path(), 0.05)
    first, second = world.place("living_room"), world.place("hallway")
    env = {**os.environ, **ros_environment(domain_id)}
    sim = subprocess.Popen(
        [
            *(sys.executable, "-m", "amiro.cli", "sim", "--ros2", "--navigation", "--json"),
            *("--camera-rate", "0", "--speed", "2", "--duration", "600"),
        ],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        client = subprocess.run(
            [sys.executable, str(SCRIPT), *map(str, (first.x, first.y, second.x, second.y))],
            env=env,
            capture_output=True,
            text=True,
            timeout=400,
        )
    finally:
        sim.send_signal(signal.SIGTERM)
        out, err = sim.communicate(timeout=30)
    assert client.returncode == 0, client.stderr
    got = json.loads(client.stdout.strip().splitlines()[-1])
    assert got["server"]
    params = got["parameters"]  # the node answers describe_parameters like any ROS 2 node
    assert params["role"][1:] == [True, "sim"]
    assert params["navigation.backend"][1:] == [True, "amiro"] and params["role"][0]
    reached = got["first"]
    print(json.dumps(got))  # the figures docs/ros2.md quotes
    assert reached["accepted"] and reached["succeeded"] and reached["error_code"] == 0
    assert reached["feedback"] > 5 and reached["frame"] == "map"
    assert reached["first_remaining_m"] > 3.0 and reached["last_remaining_m"] < 0.35
    assert reached["navigation_time_s"] > 1.0 and reached["recoveries"] == 0
    assert reached["to_goal_m"] < 0.35  # the simulator's true pose
    halted = got["second"]
    assert halted["accepted"] and halted["cancel_accepted"] and halted["canceled"]
    assert halted["canceled_at_m"] < 0.5 * halted["first_remaining_m"]
    assert halted["to_goal_m"] > 0.5  # stopped on the way, not at the goal
    assert got["moved_after_cancel_m"] < 0.05
    assert sim.returncode == 0, err
    report = json.loads(out.strip().splitlines()[-1])
    assert report["actions"]["ros2_serve:/navigate_to_pose"]["errors"] == 0
