"""What the whole system refuses on a real robot, before connecting to it, and what needs
the simulator: one-line errors (exit 2 at the CLI)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
import yaml

from amiro.cli import main
from amiro.core.clock import SimClock
from amiro.core.config import ConfigError
from amiro.core.runtime import Runtime
from amiro.perception.config import PerceptionConfig
from amiro.perception.stack import build_people_finder
from amiro.scenarios.common import run_scenario
from amiro.sim.simulator import build_sim
from amiro.system import SystemConfig, build_system

ROBOT: dict[str, Any] = {"robot": {"adapter": "ros2", "profile": "amiro_sim"}}
CAMERA: dict[str, Any] = {
    "perception": {"backend": "camera"},
    "activity": {"backend": "camera-onnx", "pose": {"model": "pose.onnx"}},
}


def test_serve_refuses_a_real_robot_with_the_simulators_perception(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = tmp_path / "robot.yaml"
    path.write_text(yaml.safe_dump(ROBOT), encoding="utf-8")
    assert main(["serve", "--config", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert "perception.backend: sim reads the simulator" in err and "camera" in err


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"activity": {"backend": "onnx"}}, "activity.backend: onnx reads the simulator"),
        ({"navigation": {"localization": "oracle"}}, "oracle is the simulator's true pose"),
        ({"home": "/nowhere/home.yaml"}, "/nowhere/home.yaml"),
        ({"navigation": {"start_place": "garage"}}, "no place named 'garage'"),
        (
            {"robot": {"adapter": "naoqi", "naoqi": {"url": "tcp://127.0.0.1:1"}}},
            "naoqi alone has no laser or camera",
        ),
    ],
)
def test_real_robot_configs_that_cannot_run_are_refused(
    change: dict[str, Any], message: str
) -> None:
    cfg = SystemConfig.model_validate({**ROBOT, **CAMERA, **change})
    with pytest.raises(ConfigError, match=message):
        build_system(cfg)


def test_the_simulator_takes_its_home_from_sim_home() -> None:
    with pytest.raises(ConfigError, match=r"home: the simulated home is sim\.home"):
        build_system(SystemConfig.model_validate({"home": "/elsewhere/home.yaml"}))


def test_scenarios_need_the_simulator() -> None:
    cfg = SystemConfig.model_validate({**ROBOT, **CAMERA})
    with pytest.raises(ConfigError, match=r"scenarios .* need the simulator"):
        run_scenario(cfg, lambda _: True, live=False, speed=None, timeout_s=1.0)


def test_the_simulated_camera_cannot_feed_the_camera_backend() -> None:
    runtime = Runtime(SimClock(), seed=1)
    sim = build_sim(runtime)
    with pytest.raises(ConfigError, match="build_camera_modules"):
        build_people_finder(sim, runtime.rng, PerceptionConfig(backend="camera"))


def test_the_embedded_system_reports_the_simulators_pose_and_people() -> None:
    system = build_system(SystemConfig())
    assert system.robot is None and system.sim is not None
    assert system.world is system.sim.world
    assert system.robot_pose() == system.sim.robot.true_pose
    assert [p.name for p in system.people()] == [r.name for r in system.config.sim.residents]
    system.stop()
