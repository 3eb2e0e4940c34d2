"""``amiro sim --ros2`` is driven by a plain rclpy script that knows nothing of amiro."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from pathlib import Path

from amiro.ros2.env import ros_environment

SCRIPT = Path(__file__).parent / "scripts" / "drive_sim.py"


def test_plain_rclpy_script_reads_scan_and_odom_and_drives(domain_id: int) -> None:
    env = {**os.environ, **ros_environment(domain_id)}
    sim = subprocess.Popen(
        [sys.executable, "-m", "amiro.cli", "sim", "--ros2", "--json", "--duration", "60"],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        client = subprocess.run(
            [sys.executable, str(SCRIPT), "2.0"],
            env=env,
            capture_output=True,
            text=True,
            timeout=60,
        )
    finally:
        sim.send_signal(signal.SIGTERM)
        out, err = sim.communicate(timeout=20)
    assert client.returncode == 0, client.stderr
    got = json.loads(client.stdout.strip().splitlines()[-1])
    assert got["scan"] > 5 and got["odom"] > 10 and got["map"] == 1
    assert got["scan_frame"] == "laser" and got["odom_frames"] == ["odom", "base_footprint"]
    assert got["beams"] > 100
    assert got["moved_m"] > 0.05  # the base followed /cmd_vel
    assert sim.returncode == 0, err
    report = json.loads(out.strip().splitlines()[-1])
    assert report["outcome"] == "stopped" and report["bridge"]["in"] > 5  # cmd_vel received
