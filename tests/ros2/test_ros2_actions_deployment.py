"""MoveTo crossing the wire: navigation in the robot process, the behaviour engine on the
edge, the cloud as usual; three OS processes over ROS 2 run hydration to its end."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from amiro.core import names
from amiro.deploy.config import DEFAULT_PUBLISH, DEFAULT_SUBSCRIBE
from amiro.deploy.launch import Launcher, load_deployment


def _write(path: Path, data: dict[str, object]) -> Path:
    path.write_text(yaml.safe_dump(data), encoding="utf-8")
    return path


def _deployment(tmp_path: Path) -> Path:
    sim = {
        "role": "sim",
        "speed": 3.0,  # as the shipped deployment: a busy edge keeps pace
        "wait_for": ["amiro_edge", "amiro_cloud"],
        "serve_actions": [names.MOVE_TO, names.FORWARD],  # FORWARD: reframing to watch
        "publish": [*DEFAULT_PUBLISH["sim"], names.LOCALIZATION],  # the pose the edge reads
        "subscribe": ["/amiro/head/cmd", "/amiro/say"],  # /cmd_vel comes from local MoveTo
    }
    edge = {
        "role": "edge",
        "heartbeat_s": 0.5,
        "call_actions": [names.MOVE_TO, names.FORWARD],
        "publish": [t for t in DEFAULT_PUBLISH["edge"] if t != "/cmd_vel"],
        "subscribe": [
            *(t for t in DEFAULT_SUBSCRIBE["edge"] if t != "/scan"),
            "/odom",
            names.LOCALIZATION,
        ],
    }
    cloud = {"role": "cloud", "watch": {"edge": 2.0, "sim": 2.0}, "stop_after_acks": 1}
    processes = [
        {"name": "sim", "config": str(_write(tmp_path / "sim.yaml", sim)), "restart": "never"},
        {"name": "edge", "config": str(_write(tmp_path / "edge.yaml", edge)), "restart": "never"},
        {
            "name": "cloud",
            "config": str(_write(tmp_path / "cloud.yaml", cloud)),
            "restart": "never",
            "ends_deployment": True,
        },
    ]
    return _write(
        tmp_path / "remote-nav.yaml",
        {"name": "remote-nav", "timeout_s": 240, "processes": processes},
    )


@pytest.mark.slow
def test_hydration_completes_with_move_to_across_processes(tmp_path: Path, domain_id: int) -> None:
    launcher = Launcher(
        load_deployment(_deployment(tmp_path)), tmp_path / "logs", domain_id=domain_id
    )
    outcome = launcher.run_all()
    assert outcome == "cloud finished"
    sim = launcher.report("sim")
    edge = launcher.report("edge")
    cloud = launcher.report("cloud")
    served = sim["actions"][f"ros2_serve:{names.MOVE_TO}"]
    called = edge["actions"][f"ros2_call:{names.MOVE_TO}"]
    assert called["sent"] >= 1 and served["received"] >= 1 and served["sent"] > 0
    assert served["errors"] == 0 and called["errors"] == 0
    assert edge["runs"] and edge["runs"][-1]["outcome"] == "completed"
    assert cloud["outcome"] == "acknowledged"
    assert all(c["exit_code"] is not None for c in launcher.summary())
    assert not launcher.unclean_exits(), launcher.unclean_exits()
