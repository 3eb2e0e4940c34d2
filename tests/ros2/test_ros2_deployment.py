"""The must-show: sim, edge and cloud as separate OS processes over ROS 2 on loopback."""

from __future__ import annotations

import json
import os
import signal
import time
from importlib import resources
from pathlib import Path
from typing import Any

from amiro.deploy.launch import Launcher, load_deployment

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


def _is_checkpoint_at(event: dict[str, Any], task: str) -> bool:
    return event.get("type") == "behavior_checkpoint" and event.get("task") == task


def _approaching_or_over(events: list[dict[str, Any]]) -> bool:
    return any(_is_checkpoint_at(e, "approach") or e["type"] == "graph_finished" for e in events)


def test_edge_killed_mid_scenario_is_detected_and_restart_resumes(
    tmp_path: Path, domain_id: int
) -> None:
    launcher = Launcher(load_deployment(DEPLOYMENT), tmp_path, domain_id=domain_id)
    cloud_events = launcher.events_path("cloud")
    launcher.start()
    try:
        # Kill while the robot drives to Maria: Search has found her, MoveTo runs, and the
        # cloud holds the checkpoint that says so.
        _wait_for(lambda: _approaching_or_over(_events(cloud_events)), 120)
        seen = _events(cloud_events)
        assert any(_is_checkpoint_at(e, "approach") for e in seen), [e["type"] for e in seen]
        os.kill(launcher.pid("edge"), signal.SIGKILL)
        outcome = launcher.run()
    finally:
        launcher.stop()

    assert outcome == "cloud finished"
    kinds = [(e["type"], e["process"]) for e in launcher.events]
    assert ("exited", "edge") in kinds and ("restarting", "edge") in kinds
    events = _events(cloud_events)
    lost = [e for e in events if e["type"] == "node_lost" and e["node"] == "edge"]
    first_edge_pid = next(
        e["pid"] for e in events if e["type"] == "node_up" and e["node"] == "edge"
    )
    back = [e for e in events if e["type"] == "node_back" and e["node"] == "edge"]
    assert lost and back and lost[0]["t"] < back[0]["t"]
    # A busy machine can make the edge miss heartbeats without dying (node_back, same pid):
    # the ledger's redelivery then reaches the running edge, which ignores the duplicate.
    restarts = [e for e in back if e["pid"] != first_edge_pid]
    assert restarts, back
    restart = restarts[0]
    killed = [e for e in lost if e["t"] < restart["t"]][-1]
    before_kill = [e for e in events if e["type"] == "behavior_checkpoint" and e["t"] < killed["t"]]
    assert before_kill[-1]["task"] == "approach"
    after = [e for e in events if e["t"] > restart["t"]]
    redelivered = [e for e in after if e["type"] == "notification_redelivered"]
    assert redelivered and redelivered[0]["resume_task"] == "approach"
    # The restarted edge resumed the behaviour at the task running at the kill, not at Search.
    resumed = [e for e in after if e["type"] == "behavior_resumed"]
    assert resumed and resumed[0]["task"] == "approach" and resumed[0]["finished"] == ["search"]
    started = [e["task"] for e in after if e["type"] == "task_started"]
    assert started[0] == "approach" and "search" not in started
    assert len([e for e in events if e["type"] == "graph_submitted"]) == 2  # no duplicate run
    # ... and ran it to its end.
    finished = [e for e in events if e["type"] == "graph_finished"]
    assert finished and finished[-1]["t"] > restart["t"]
    assert finished[-1]["outcome"] == "completed"
    acks = [e for e in events if e["type"] == "ack_received"]
    assert len(acks) == 1 and acks[0]["t"] > restart["t"]
    # Every process ended cleanly (SIGTERM handled: exit code 0), none left running.
    assert all(c["exit_code"] is not None for c in launcher.summary())
    assert not launcher.unclean_exits(), launcher.unclean_exits()
    cloud = launcher.report("cloud")
    assert cloud["outcome"] == "acknowledged" and cloud["pending_notifications"] == []
