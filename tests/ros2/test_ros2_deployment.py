"""The must-show: sim, edge and cloud as separate OS processes over ROS 2 on loopback."""

from __future__ import annotations

import json
import os
import signal
import time
from importlib import resources
from pathlib import Path
from typing import Any

from amiro.ros2.launch import Launcher, load_deployment

DEPLOYMENT = Path(str(resources.files("amiro").joinpath("data/deployments/hydration.yaml")))


def _events(path: Path) -> list[dict[str, Any]]:
    if not path.is_file():
        return []
    return [json.loads(line) for line in path.read_text().splitlines() if line.strip()]


def _wait_for(pred: Any, timeout_s: float) -> bool:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if pred():
            return True
        time.sleep(0.1)
    return False


def test_edge_killed_mid_scenario_is_detected_and_restart_resumes(
    tmp_path: Path, domain_id: int
) -> None:
    launcher = Launcher(load_deployment(DEPLOYMENT), tmp_path, domain_id=domain_id)
    cloud_events = launcher.events_path("cloud")
    launcher.start()
    try:
        searching = _wait_for(
            lambda: any(e.get("type") == "task_started" for e in _events(cloud_events)), 40
        )
        assert searching, "the edge never started the hydration behaviour"
        time.sleep(1.0)  # mid-task: the robot is looking for Maria
        os.kill(launcher.pid("edge"), signal.SIGKILL)
        outcome = launcher.run()
    finally:
        launcher.stop()

    assert outcome == "cloud finished"
    kinds = [(e["type"], e["process"]) for e in launcher.events]
    assert ("exited", "edge") in kinds and ("restarting", "edge") in kinds
    events = _events(cloud_events)
    lost = [e for e in events if e["type"] == "node_lost" and e["node"] == "edge"]
    back = [e for e in events if e["type"] == "node_back" and e["node"] == "edge"]
    assert lost and back and lost[0]["t"] < back[0]["t"]
    assert any(e["type"] == "notification_redelivered" for e in events)
    # The restarted edge ran the behaviour again from the redelivered notification, to its end.
    finished = [e for e in events if e["type"] == "graph_finished"]
    assert finished and finished[-1]["t"] > back[0]["t"]
    assert finished[-1]["outcome"] == "completed"
    acks = [e for e in events if e["type"] == "ack_received"]
    assert len(acks) == 1 and acks[0]["t"] > back[0]["t"]
    # Every process ended cleanly (SIGTERM handled: exit code 0), none left running.
    assert all(c["exit_code"] is not None for c in launcher.summary())
    assert not launcher.unclean_exits(), launcher.unclean_exits()
    cloud = json.loads(launcher.report_path("cloud").read_text())
    assert cloud["outcome"] == "acknowledged" and cloud["pending_notifications"] == []
