"""Live /tf and /tf_static: a plain rclpy listener, knowing nothing of amiro, sees the whole
REP-105 tree of a split deployment (``amiro sim --ros2`` plus ``amiro node edge``).

These use the venv's tf2_msgs, which setup builds; the fixture builds it only if setup has
not (a no-op otherwise), the way setup does.
"""

from __future__ import annotations

import importlib
import json
import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from amiro.core.messages import Header, Quaternion, TransformStamped, Vector3
from amiro.ros2.env import ros_environment
from amiro.ros2.msgbuild import build_package
from amiro.ros2.routes import route
from amiro.ros2.types import RclpyTypes

SCRIPT = Path(__file__).parent / "scripts" / "listen_tf.py"


@pytest.fixture(scope="module", autouse=True)
def tf2_msgs_in_venv() -> None:
    build_package("tf2_msgs")
    importlib.invalidate_caches()


def test_tf_codecs_round_trip_through_rclpy_messages() -> None:
    tf = TransformStamped(
        Header(3.25, "camera_link"),
        "camera",
        Vector3(0.1, 0.0, 1.15),
        Quaternion(-0.5, 0.5, -0.5, 0.5),
    )
    types = RclpyTypes()
    for topic in ("/tf", "/tf_static"):
        codec = route(topic).codec
        msg = codec.encode(types, tf, 9.0)
        assert type(msg).__module__.startswith("tf2_msgs.msg")
        assert codec.decode(msg) == tf
    assert route("/tf_static").latched and not route("/tf").latched


def _start(args: list[str], env: dict[str, str]) -> subprocess.Popen[str]:
    return subprocess.Popen(
        [sys.executable, "-m", "amiro.cli", *args, "--json"],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


def _stop(proc: subprocess.Popen[str]) -> dict[str, object]:
    proc.send_signal(signal.SIGTERM)
    out, err = proc.communicate(timeout=30)
    assert proc.returncode == 0, err
    report: dict[str, object] = json.loads(out.strip().splitlines()[-1])
    return report


def test_plain_listener_gets_the_tree_from_sim_and_edge(domain_id: int) -> None:
    env = {**os.environ, **ros_environment(domain_id)}
    sim = _start(["sim", "--ros2", "--duration", "120"], env)
    edge = _start(["node", "edge"], env)
    try:
        client = subprocess.run(
            [sys.executable, str(SCRIPT), "3.0"],
            env=env,
            capture_output=True,
            text=True,
            timeout=90,
        )
    finally:
        sim_report, edge_report = _stop(sim), _stop(edge)
    assert client.returncode == 0, client.stderr
    got = json.loads(client.stdout.strip().splitlines()[-1])
    # the robot process: odometry on /tf, the same numbers /odom carries at the same stamps
    assert ["odom", "base_footprint"] in got["tf"] and ["base_link", "camera_link"] in got["tf"]
    # (the first few may precede the /odom subscription's discovery, the last its delivery)
    assert got["matched"] > 10 and got["matched"] >= 0.9 * got["odom_tf"], got
    assert got["worst_difference"] < 1e-6 and got["moved_m"] > 0.05
    # ... and the mounts, once, on the latched /tf_static
    assert got["tf_static"] == [
        ["base_footprint", "base_link"],
        ["base_link", "laser"],
        ["camera_link", "camera"],
    ]
    # the edge: AMCL's map -> odom, which puts the robot where the simulator says it is
    assert ["map", "odom"] in got["tf"]
    assert got["localization_error_m"] is not None and got["localization_error_m"] < 0.3
    assert sim_report["bridge"]["skipped"] == []  # type: ignore[index]
    assert edge_report["bridge"]["skipped"] == []  # type: ignore[index]
