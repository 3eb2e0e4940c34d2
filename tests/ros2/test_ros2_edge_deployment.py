"""Across OS processes, the edge finds Maria and recognises her drinking with the embedded
system's real modules, fed only by the robot process's bridged camera and skeleton topics."""

from __future__ import annotations

import json
from importlib import resources
from pathlib import Path
from typing import Any

import pytest

from amiro.deploy.launch import Launcher, load_deployment

DEPLOYMENT = Path(str(resources.files("amiro").joinpath("data/deployments/hydration.yaml")))


def _events(path: Path) -> list[dict[str, Any]]:
    return [json.loads(line) for line in path.read_text().splitlines() if line.strip()]


@pytest.mark.slow
def test_hydration_completes_with_real_perception_and_activity_on_the_edge(
    tmp_path: Path, domain_id: int
) -> None:
    launcher = Launcher(load_deployment(DEPLOYMENT), tmp_path, domain_id=domain_id)
    outcome = launcher.run_all()
    assert outcome == "cloud finished"
    assert not launcher.unclean_exits(), launcher.unclean_exits()
    edge = launcher.report("edge")
    assert edge["perception"] == "sim-detector" and edge["activity"] == "onnx"
    assert edge["runs"] and edge["runs"][-1]["outcome"] == "completed"
    received = edge["received"]
    assert received["frames"] > 100 and received["joint_states"] > 100
    assert received["camera_info"] > 0 and received["skeletons"] > 30
    assert edge["people_estimates"] > 0  # Maria placed in the map from the bridged frames
    events = _events(launcher.events_path("edge"))
    watched = [
        e for e in events if e["type"] == "task_finished" and e["task_type"] == "RecognizeActivity"
    ]
    assert watched and watched[-1]["detail"]["activity"] == "drink_water"
    # Fall monitoring is off on the split edge (hydration-edge-system.yaml): none raised.
    assert not [e for e in events if e["type"] == "fall_detected"]
