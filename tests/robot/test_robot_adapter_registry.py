"""Robot adapters are chosen by name through the registry: a new one is its own class plus one
``register`` call, and the whole system builds on it."""

from __future__ import annotations

from typing import Any

import pytest

from amiro.core import registry
from amiro.core.config import ConfigError, parse
from amiro.core.runtime import Runtime
from amiro.robot.adapter import adapter_type
from amiro.robot.build import RealRobot
from amiro.robot.config import RobotConfig
from amiro.sim.adapter import SimAdapter
from amiro.system import SystemConfig, build_system


class CountingSimAdapter(SimAdapter):
    """A plugin: the simulated home, counting how often it was built."""

    built = 0

    @classmethod
    def build(cls, runtime: Runtime, config: Any) -> CountingSimAdapter:
        cls.built += 1
        return super().build(runtime, config)


@pytest.fixture
def plugin(monkeypatch: pytest.MonkeyPatch) -> type[CountingSimAdapter]:
    shipped = {kind: dict(entries) for kind, entries in registry._REGISTRY.items()}
    monkeypatch.setattr(registry, "_REGISTRY", shipped)  # the plugin leaves with the test
    registry.register("robot", "counting-sim", f"{__name__}:CountingSimAdapter")
    return CountingSimAdapter


def test_shipped_adapters_are_registered_by_name() -> None:
    assert {"sim", "ros2", "naoqi"} <= set(registry.names("robot"))
    assert adapter_type("sim") is SimAdapter and adapter_type("ros2") is RealRobot
    assert SimAdapter.simulated and not RealRobot.simulated


def test_an_unknown_adapter_is_one_line_naming_the_choices() -> None:
    with pytest.raises(ConfigError) as err:
        parse(RobotConfig, {"adapter": "gazebo"}, "robot.yaml")
    message = str(err.value)
    assert "\n" not in message and "gazebo" in message
    assert "naoqi, ros2, sim" in message


def test_the_system_builds_on_a_registered_plugin_adapter(
    plugin: type[CountingSimAdapter],
) -> None:
    cfg = SystemConfig.model_validate({"robot": {"adapter": "counting-sim"}})
    system = build_system(cfg)
    assert isinstance(system.adapter, plugin) and plugin.built == 1
    assert system.sim is system.adapter.simulation  # the simulated home's ground truth
    system.start()
    system.runtime.spin_for(2.0)
    assert system.robot_pose() is not None and system.adapter.stats()["collisions"] == 0
    system.stop()
