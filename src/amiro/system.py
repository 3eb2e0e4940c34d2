"""The embedded system: one process, one bus, the simulated home and every module.

``build_system`` wires the simulator (the default robot), navigation, perception, activity,
dialogue, the smart environment and the behaviour engine from one :class:`SystemConfig`.
Scenarios, ``amiro serve`` and the tests all start from here.
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Literal

from pydantic import Field

import amiro.behavior.tasks  # noqa: F401 - registers the task types
from amiro.activity.oracle import OracleActivityRecognizer
from amiro.behavior.engine import BehaviorEngine, EngineConfig
from amiro.behavior.handlers import HandlerRegistry, yaml_handler
from amiro.behavior.notifications import NotificationHandlerNode, UserProfile
from amiro.core.clock import Clock, SimClock
from amiro.core.config import ConfigError, Section
from amiro.core.gridmap import load_map
from amiro.core.runtime import Runtime
from amiro.dialogue.oracle import OracleUnderstanding
from amiro.dialogue.output import BusSpeechOutput
from amiro.environment.rules import RulesNode, ThresholdRule
from amiro.environment.simulated import SimulatedSensorsConfig, SimulatedSensorsNode
from amiro.navigation.config import NavigationConfig
from amiro.navigation.move_to import MoveToNode
from amiro.navigation.stack import build_navigation
from amiro.perception.oracle import OraclePeopleFinder
from amiro.sim.config import SimConfig
from amiro.sim.simulator import Simulation, build_sim
from amiro.sim.world import default_home_path


def shipped_behavior(name: str) -> Path:
    return Path(str(resources.files("amiro").joinpath(f"data/behaviors/{name}.yaml")))


class PerceptionConfig(Section):
    backend: Literal["oracle"] = "oracle"
    position_noise_m: float = Field(default=0.1, ge=0.0)


class ActivityConfig(Section):
    backend: Literal["oracle"] = "oracle"
    accuracy: float = Field(default=0.95, ge=0.0, le=1.0)


class DialogueConfig(Section):
    nlu: Literal["oracle"] = "oracle"
    words_per_second: float = Field(default=2.5, gt=0.0)


HOT_ROOM = ThresholdRule(
    name="hot_room", sensor="temperature", above=28.0, kind="hydration", priority=5
)


class EnvironmentConfig(Section):
    home_id: str = "home"
    sensors: SimulatedSensorsConfig = Field(default_factory=SimulatedSensorsConfig)
    rules: tuple[ThresholdRule, ...] = (HOT_ROOM,)


class BehaviorConfig(Section):
    engine: EngineConfig = Field(default_factory=EngineConfig)
    handlers: dict[str, Path] = Field(
        default_factory=dict, description="notification kind -> behaviour YAML"
    )


class SystemConfig(Section):
    seed: int = 1
    sim: SimConfig = Field(default_factory=SimConfig)
    navigation: NavigationConfig = Field(default_factory=NavigationConfig)
    perception: PerceptionConfig = Field(default_factory=PerceptionConfig)
    activity: ActivityConfig = Field(default_factory=ActivityConfig)
    dialogue: DialogueConfig = Field(default_factory=DialogueConfig)
    environment: EnvironmentConfig = Field(default_factory=EnvironmentConfig)
    behavior: BehaviorConfig = Field(default_factory=BehaviorConfig)


@dataclass
class System:
    config: SystemConfig
    runtime: Runtime
    sim: Simulation
    navigation: MoveToNode
    engine: BehaviorEngine
    handlers: HandlerRegistry
    notifications: NotificationHandlerNode
    sensors: SimulatedSensorsNode
    rules: RulesNode

    def start(self) -> None:
        self.runtime.start()

    def stop(self) -> None:
        self.runtime.stop()


def _nav_map_path(cfg: SystemConfig) -> Path:
    if cfg.navigation.map is not None:
        return cfg.navigation.map
    return (cfg.sim.home or default_home_path()).with_name("map.yaml")


def build_system(cfg: SystemConfig, clock: Clock | None = None) -> System:
    """Everything in one runtime, seeded by ``cfg.seed``."""
    runtime = Runtime(clock or SimClock(), seed=cfg.seed)
    sim = build_sim(runtime, cfg.sim)
    world = sim.world
    places = {name: world.place(name) for name in world.home.places}
    navigation = runtime.add(build_navigation(load_map(_nav_map_path(cfg)), places, cfg.navigation))

    rng_perception, rng_activity = runtime.rng.spawn(2)
    modules = {
        "clock": runtime.clock,
        "world": world,
        "navigation": navigation,
        "perception": OraclePeopleFinder(sim, rng_perception, cfg.perception.position_noise_m),
        "activity": OracleActivityRecognizer(sim, rng_activity, cfg.activity.accuracy),
        "speech": BusSpeechOutput(runtime.bus, cfg.dialogue.words_per_second),
        "nlu": OracleUnderstanding(),
    }
    engine = runtime.add(BehaviorEngine(config=cfg.behavior.engine, modules=modules))
    handlers = HandlerRegistry(engine)
    behaviors = {"hydration": shipped_behavior("hydration"), **cfg.behavior.handlers}
    for kind, path in behaviors.items():
        if not path.is_file():
            raise ConfigError(f"behavior.handlers.{kind}: {path}: no such file")
        handlers.register(kind, yaml_handler(path), replace=True)

    profiles = {r.name: UserProfile(r.name, r.name.title(), r.language) for r in cfg.sim.residents}
    notifications = runtime.add(NotificationHandlerNode(engine, handlers, profiles))
    sensors = runtime.add(
        SimulatedSensorsNode(
            list(world.home.rooms), cfg.environment.sensors, cfg.environment.home_id
        )
    )
    rules = runtime.add(RulesNode(list(cfg.environment.rules), cfg.environment.home_id))
    return System(cfg, runtime, sim, navigation, engine, handlers, notifications, sensors, rules)
