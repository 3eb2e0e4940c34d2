"""The embedded system: one process, one bus, the simulated home and every module.

``build_system`` wires the simulator (the default robot), navigation, perception, activity,
dialogue, the smart environment and the behaviour engine from one :class:`SystemConfig`.
Scenarios, ``amiro serve`` and the tests all start from here.
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

from pydantic import Field

import amiro.behavior.tasks  # noqa: F401 - registers the task types
from amiro.activity.config import ActivityConfig
from amiro.activity.fall import FallMonitorNode
from amiro.activity.stack import build_activity_recognizer
from amiro.behavior.engine import BehaviorEngine, EngineConfig
from amiro.behavior.handlers import HandlerRegistry, yaml_handler
from amiro.behavior.notifications import NotificationHandlerNode, UserProfile
from amiro.core.clock import Clock, SimClock
from amiro.core.config import ConfigError, Section
from amiro.core.gridmap import load_map
from amiro.core.runtime import Runtime
from amiro.dialogue.config import DialogueConfig
from amiro.dialogue.profiles import SpeakerProfile
from amiro.dialogue.stack import Dialogue, build_dialogue
from amiro.environment.assembly import Environment, add_environment
from amiro.environment.config import EnvironmentConfig
from amiro.environment.dialogue_sources import environment_sources
from amiro.environment.rules import RulesNode
from amiro.environment.simulated import SimulatedSensorsNode
from amiro.navigation.config import NavigationConfig
from amiro.navigation.move_to import MoveToNode
from amiro.navigation.primitives import PrimitivesNode
from amiro.navigation.stack import build_navigation
from amiro.perception.config import PerceptionConfig
from amiro.perception.stack import build_people_finder
from amiro.robot.config import RobotConfig
from amiro.sim.config import SimConfig
from amiro.sim.simulator import Simulation, build_sim
from amiro.sim.world import default_home_path

SHIPPED_BEHAVIORS = ("hydration", "fall", "go_to")


def shipped_behavior(name: str) -> Path:
    return Path(str(resources.files("amiro").joinpath(f"data/behaviors/{name}.yaml")))


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
    robot: RobotConfig = Field(default_factory=RobotConfig)


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
    dialogue: Dialogue
    environment: Environment

    def start(self) -> None:
        self.runtime.start()

    def stop(self) -> None:
        self.runtime.stop()
        self.environment.close()


def nav_map_path(cfg: SystemConfig) -> Path:
    if cfg.navigation.map is not None:
        return cfg.navigation.map
    return (cfg.sim.home or default_home_path()).with_name("map.yaml")


def build_system(cfg: SystemConfig, clock: Clock | None = None) -> System:
    """Everything in one runtime, seeded by ``cfg.seed``."""
    if cfg.robot.adapter != "sim":
        raise ConfigError(
            f"robot.adapter: {cfg.robot.adapter}: the whole stack runs on the simulated home "
            "only so far (perception and activity read the simulator); drive a real robot "
            "with `amiro robot run` or the split deployment (`amiro launch`)"
        )
    runtime = Runtime(clock or SimClock(), seed=cfg.seed)
    sim = build_sim(runtime, cfg.sim)
    world = sim.world
    places = {name: world.place(name) for name in world.home.places}
    rooms = list(world.home.rooms)
    # As an operator would on /initialpose: AMCL starts where the robot was put down, unless
    # navigation.start_place is None (global localisation from an unknown pose).
    initial_pose = None if cfg.navigation.start_place is None else sim.robot.true_pose
    navigation = runtime.add(
        build_navigation(load_map(nav_map_path(cfg)), places, cfg.navigation, initial_pose)
    )
    runtime.add(PrimitivesNode(speed=min(0.2, cfg.navigation.max_speed)))  # forward / rotate

    rng_perception, rng_activity = runtime.rng.spawn(2)
    voices = {
        r.name: SpeakerProfile.model_validate({"lang": r.language}) for r in cfg.sim.residents
    }
    modules: dict[str, Any] = {}  # filled below; the engine keeps this very dict
    engine = runtime.add(BehaviorEngine(config=cfg.behavior.engine, modules=modules))
    handlers = HandlerRegistry(engine)

    def submit(kind: str, payload: dict[str, Any]) -> object:
        """Dialogue requests (``go_to``) become behaviours."""
        return engine.submit(handlers.build(kind, payload))

    sensors = runtime.add(
        SimulatedSensorsNode(rooms, cfg.environment.sensors, cfg.environment.home_id)
    )
    rules = runtime.add(RulesNode(list(cfg.environment.rules), cfg.environment.home_id))
    environment = add_environment(runtime, rooms, cfg.environment, sensors, rules)
    sources = environment_sources(runtime, environment, rooms)
    dialogue = build_dialogue(runtime, cfg.dialogue, voices, submit=submit, sources=sources)
    activity = build_activity_recognizer(sim, rng_activity, cfg.activity)
    modules.update(
        {
            "clock": runtime.clock,
            "world": world,
            "navigation": navigation,
            "perception": build_people_finder(
                sim, rng_perception, cfg.perception, lambda: navigation.pose
            ),
            "activity": activity,
            "speech": dialogue.speech,
            "nlu": dialogue.nlu,
        }
    )
    behaviors = {name: shipped_behavior(name) for name in SHIPPED_BEHAVIORS}
    behaviors.update(cfg.behavior.handlers)
    for kind, path in behaviors.items():
        if not path.is_file():
            raise ConfigError(f"behavior.handlers.{kind}: {path}: no such file")
        handlers.register(kind, yaml_handler(path), replace=True)
    if cfg.activity.fall_detection:
        residents = sim.residents.residents
        runtime.add(
            FallMonitorNode(activity, handlers, lambda: list(residents), cfg.activity.fall_period_s)
        )

    profiles = {r.name: UserProfile(r.name, r.name.title(), r.language) for r in cfg.sim.residents}
    notifications = runtime.add(NotificationHandlerNode(engine, handlers, profiles))
    return System(
        cfg,
        runtime,
        sim,
        navigation,
        engine,
        handlers,
        notifications,
        sensors,
        rules,
        dialogue,
        environment,
    )
