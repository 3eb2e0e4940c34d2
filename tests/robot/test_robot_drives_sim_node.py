"""The ROS 2 adapter drives ``amiro sim --ros2`` in another process as it would a real robot."""

from __future__ import annotations

import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

from amiro.core.clock import SimClock
from amiro.core.messages import LaserScan, Odometry, Twist
from amiro.core.runtime import Runtime
from amiro.robot.profile import load_profile
from amiro.robot.ros2_adapter import Ros2RobotNode
from amiro.ros2.context import RosContext
from amiro.ros2.env import ros_environment

PROFILE = """\
name: amiro_sim
base: omnidirectional
limits: {max_linear: 0.3, max_angular: 0.6, max_linear_accel: 0.5, max_angular_accel: 2.0}
frames: {odom: odom, base: base_footprint, laser: laser}
topics: {scan: /scan, odom: /odom, cmd_vel: /cmd_vel, joint_states: /joint_states}
"""


def test_adapter_reads_and_drives_the_simulator_process(robot_domain: int, tmp_path: Path) -> None:
    (tmp_path / "amiro_sim.yaml").write_text(PROFILE, encoding="utf-8")
    profile = load_profile(tmp_path / "amiro_sim.yaml")
    env = {**os.environ, **ros_environment(robot_domain)}
    sim = subprocess.Popen(
        [sys.executable, "-m", "amiro.cli", "sim", "--ros2", "--json", "--duration", "60"],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    ros = RosContext("amiro_robot_adapter", robot_domain)
    runtime = Runtime(SimClock(speed=1.0))
    adapter = runtime.add(Ros2RobotNode(ros, profile))
    odoms: list[Odometry] = []
    scans: list[LaserScan] = []
    runtime.bus.subscribe("/odom", Odometry, odoms.append)
    runtime.bus.subscribe("/scan", LaserScan, scans.append)
    try:
        runtime.start()
        assert runtime.spin_until(lambda: bool(odoms) and bool(scans), 30.0)
        start = odoms[-1].pose.orientation.yaw
        cmd = runtime.bus.publisher("/cmd_vel", Twist)
        deadline = time.monotonic() + 3.0
        while time.monotonic() < deadline:
            cmd.publish(Twist.planar(0.0, 0.0, 2.0))  # turn on the spot, capped at 0.6 rad/s
            runtime.spin_for(0.1)
        turned = abs(math.remainder(odoms[-1].pose.orientation.yaw - start, math.tau))
    finally:
        runtime.stop()
        ros.close()
        sim.send_signal(signal.SIGTERM)
        sim.communicate(timeout=20)
    assert sim.returncode == 0
    assert scans[-1].header.frame_id == "laser" and len(scans[-1].ranges) >= 100
    assert 0.5 < turned < 0.6 * 3.0 + 0.2  # it turned, no faster than the profile allows
    assert max(abs(o.twist.angular.z) for o in odoms) <= 0.6 + 1e-6
    assert adapter.limiter.clamped > 0 and adapter.stats.errors == 0
