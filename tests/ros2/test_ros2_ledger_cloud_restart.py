"""A cloud killed mid-scenario comes back with its pending notification: the launcher
restarts it, it loads its ledger from the log dir, and the behaviour running on the edge
ends with exactly one acknowledgement."""

from __future__ import annotations

import json
import os
import signal
import time
from importlib import resources
from pathlib import Path
from typing import Any

import pytest
import yaml

from amiro.deploy.launch import Launcher, load_deployment
from amiro.deploy.ledger_store import LedgerStore

DEPLOYMENTS = Path(str(resources.files("amiro").joinpath("data/deployments")))


def _deployment(tmp_path: Path) -> Path:
    """The shipped hydration deployment, its time at 2x instead of 3x: the acknowledgement
    must come after the restarted cloud listens (an ack sent while the cloud is down is
    lost, see docs/deployment.md), also on a busy machine."""
    sim = yaml.safe_load((DEPLOYMENTS / "hydration-sim.yaml").read_text())
    sim["speed"] = 2.0
    (tmp_path / "sim.yaml").write_text(yaml.safe_dump(sim))
    deployment = yaml.safe_load((DEPLOYMENTS / "hydration.yaml").read_text())
    for process in deployment["processes"]:
        name = process["name"]
        process["config"] = str(
            tmp_path / "sim.yaml" if name == "sim" else DEPLOYMENTS / process["config"]
        )
    path = tmp_path / "deployment.yaml"
    path.write_text(yaml.safe_dump(deployment))
    return path


def _events(path: Path) -> list[dict[str, Any]]:
    if not path.is_file():
        return []
    return [json.loads(line) for line in path.read_text().splitlines() if line.strip()]


@pytest.mark.slow
def test_cloud_killed_mid_scenario_restarts_with_its_ledger(tmp_path: Path, domain_id: int) -> None:
    launcher = Launcher(load_deployment(_deployment(tmp_path)), tmp_path, domain_id=domain_id)
    cloud_events = launcher.events_path("cloud")
    launcher.start()
    try:
        ledger = LedgerStore(tmp_path / "cloud-ledger.json")
        deadline = time.monotonic() + 120
        while not ledger.load().checkpoints and time.monotonic() < deadline:
            time.sleep(0.1)  # killed once the checkpoint is on disk, not just received
        before = _events(cloud_events)
        assert any(e["type"] == "behavior_checkpoint" for e in before), before
        assert not any(e["type"] == "ack_received" for e in before)
        os.kill(launcher.pid("cloud"), signal.SIGKILL)
        outcome = launcher.run()
    finally:
        launcher.stop()

    assert outcome == "cloud finished"
    kinds = [(e["type"], e["process"]) for e in launcher.events]
    assert ("exited", "cloud") in kinds and ("restarting", "cloud") in kinds
    cloud = launcher.report("cloud")  # the restarted cloud's
    assert cloud["ledger"]["restored"] == 1 and cloud["ledger"]["corrupt"] == 0
    assert cloud["pending_notifications"] == [] and len(cloud["acks"]) == 1
    assert LedgerStore(tmp_path / "cloud-ledger.json").load().pending == {}
    edge = launcher.report("edge")
    assert [r["outcome"] for r in edge["runs"]] == ["completed"]  # one run, not a second
    events = _events(cloud_events)  # both clouds' events, appended
    restarted = events[len(before) :]  # (the first cloud's, up to the kill, come before)
    resent = [e for e in restarted if e["type"] == "notification_redelivered"]
    # The restarted cloud re-sends it with its checkpoint (again if a busy machine delays
    # the edge's heartbeats); the first cloud may have re-sent it before the checkpoint came.
    assert cloud["redelivered"] >= 1 and resent and resent[0]["resume_task"] is not None
    assert len([e for e in events if e["type"] == "ack_received"]) == 1
    assert not launcher.unclean_exits(), launcher.unclean_exits()
