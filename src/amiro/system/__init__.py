"""The embedded system: one process, one bus, the robot and every module.

``build_system`` wires the robot (the simulated home by default, or a real robot's ROS 2 /
NAOqi adapters with ``robot.adapter``), navigation, perception, activity, dialogue, the smart
environment and the behaviour engine from one :class:`SystemConfig`.  Scenarios,
``amiro serve`` and the tests all start from here.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from pydantic import Field

# importing registers the task types, the plans' steps (Sequence, CheckDoor) among them
import amiro.behavior.planning.tasks
import amiro.behavior.tasks  # noqa: F401
from amiro.activity.config import ActivityConfig
from amiro.activity.fall import FallMonitorNode
from amiro.activity.ports import ActivityRecognizer
from amiro.activity.stack import build_activity_recognizer
from amiro.behavior.engine import BehaviorEngine, EngineConfig
from amiro.behavior.handlers import HandlerRegistry, yaml_handler
from amiro.behavior.modules import Localized, Modules
from amiro.behavior.notifications import NotificationHandlerNode, UserProfile
from amiro.behavior.planning.config import PlanningConfig
from amiro.core.clock import Clock, SimClock, WallClock
from amiro.core.config import ConfigError, Section
from amiro.core.gridmap import load_map
from amiro.core.messages import Pose2D
from amiro.core.runtime import Runtime
from amiro.dialogue.config import DialogueConfig
from amiro.dialogue.profiles import household_voices
from amiro.dialogue.stack import Dialogue, build_dialogue, text_hearing
from amiro.environment.assembly import Environment, add_environment
from amiro.environment.config import EnvironmentConfig
from amiro.environment.rules import RulesNode
from amiro.environment.simulated import SimulatedSensorsNode
from amiro.home.household import Person
from amiro.home.world import World, default_home_path
from amiro.navigation.config import NavigationConfig
from amiro.navigation.move_to import MoveToNode
from amiro.navigation.primitives import PrimitivesNode
from amiro.navigation.stack import build_navigation
from amiro.perception.config import PerceptionConfig
from amiro.perception.ports import PeopleFinder, TracksPeople
from amiro.perception.stack import PoseSource, build_people_finder
from amiro.robot.adapter import RobotAdapter, adapter_type
from amiro.robot.build import RealRobot
from amiro.robot.camera import HeadCamera
from amiro.robot.config import RobotConfig
from amiro.robot.velocity_mux import VelocityMuxNode
from amiro.sim.adapter import SimAdapter
from amiro.sim.config import SimConfig
from amiro.sim.simulator import Simulation
from amiro.sim.skeletons import SkeletonCamera
from amiro.system.dialogue_sources import environment_sources

if TYPE_CHECKING:
    from amiro.activity.recognizer import SkeletonSource
    from amiro.behavior.planning.executive import (
        PlanExecutive,  # these load onnxruntime / OpenCV: only when their backend is chosen
    )
    from amiro.perception.camera_finder import CameraPeopleFinder

SHIPPED_BEHAVIORS = ("hydration", "fall", "go_to")


def shipped_behavior(name: str) -> Path:
    return Path(str(resources.files("amiro").joinpath(f"data/behaviors/{name}.yaml")))


class PlannerSection(PlanningConfig):
    """``behavior.planner``: the PDDL planning executive, on when the section is present."""

    people: dict[str, str] = Field(
        default_factory=dict, description="where each person is believed to be (person -> room)"
    )


class BehaviorConfig(Section):
    engine: EngineConfig = Field(default_factory=EngineConfig)
    planner: PlannerSection | None = Field(
        default=None, description="declarative planning with re-planning (docs/planning.md)"
    )
    handlers: dict[str, Path] = Field(
        default_factory=dict, description="notification kind -> behaviour YAML"
    )


class SystemConfig(Section):
    seed: int = 1
    home: Path | None = Field(
        default=None,
        description="the home's semantic YAML (rooms, places, seats); a real robot's home "
        "needs its own, beside its map (navigation.map); default: sim.home, else the "
        "shipped apartment",
    )
    sim: SimConfig = Field(default_factory=SimConfig)
    navigation: NavigationConfig = Field(default_factory=NavigationConfig)
    perception: PerceptionConfig = Field(default_factory=PerceptionConfig)
    activity: ActivityConfig = Field(default_factory=ActivityConfig)
    dialogue: DialogueConfig = Field(default_factory=DialogueConfig)
    environment: EnvironmentConfig = Field(default_factory=EnvironmentConfig)
    behavior: BehaviorConfig = Field(default_factory=BehaviorConfig)
    robot: RobotConfig = Field(default_factory=RobotConfig)
    household: list[Person] = Field(
        default_factory=list,
        description="the people the robot serves; default: the simulated home's residents",
    )

    def people(self) -> list[Person]:
        """The household: as configured, else the simulator's residents as persons."""
        if self.household:
            return list(self.household)
        return [Person(name=r.name, language=r.language, voice=r.voice) for r in self.sim.residents]


@dataclass(frozen=True)
class PersonInView:
    name: str
    x: float
    y: float
    activity: str  # "" when not known


@dataclass
class System:
    """What :func:`build_system` made, on one robot adapter."""

    config: SystemConfig
    runtime: Runtime
    adapter: RobotAdapter
    world: World
    navigation: MoveToNode
    engine: BehaviorEngine
    handlers: HandlerRegistry
    notifications: NotificationHandlerNode
    sensors: SimulatedSensorsNode
    rules: RulesNode
    dialogue: Dialogue
    environment: Environment
    camera_people: CameraPeopleFinder | None = None  # a real robot's camera tracks
    planner: PlanExecutive | None = None  # behavior.planner: goals become planned behaviours

    @property
    def sim(self) -> Simulation | None:
        """The simulated home, when the adapter is the simulator."""
        return self.adapter.simulation if isinstance(self.adapter, SimAdapter) else None

    @property
    def robot(self) -> RealRobot | None:
        """A real robot's adapters, when the adapter is one."""
        return self.adapter if isinstance(self.adapter, RealRobot) else None

    def start(self) -> None:
        self.runtime.start()

    def stop(self) -> None:
        self.runtime.stop()
        self.adapter.close()  # after the runtime: the adapters' last commands go out
        self.environment.close()

    def robot_pose(self) -> Pose2D | None:
        """The simulator's true pose, or a real robot's localisation estimate."""
        return self.sim.robot.true_pose if self.sim is not None else self.navigation.pose

    def people(self) -> list[PersonInView]:
        """Who is where: the simulator's residents, or the people a real robot's camera
        tracks (their activity unknown here)."""
        if self.sim is not None:
            residents = self.sim.residents.residents.values()
            return [PersonInView(r.name, r.x, r.y, r.activity) for r in residents if r.present]
        if self.camera_people is None:
            return []
        return [
            PersonInView(t.name or t.id, t.position.x, t.position.y, "")
            for t in self.camera_people.tracker.tracks
            if t.confirmed
        ]

    def require_sim(self, what: str) -> Simulation:
        """The simulated home, for ``what`` (a scenario, a ground-truth report)."""
        if self.sim is None:
            raise ConfigError(f"{what} needs the simulated home (robot.adapter: sim)")
        return self.sim


def home_path(cfg: SystemConfig) -> Path:
    return cfg.home or cfg.sim.home or default_home_path()


def nav_map_path(cfg: SystemConfig) -> Path:
    if cfg.navigation.map is not None:
        return cfg.navigation.map
    return home_path(cfg).with_name("map.yaml")


@dataclass
class Senses:
    """The modules that read the robot's head: people finding and activity recognition."""

    perception: PeopleFinder
    activity: ActivityRecognizer

    def modules(self, runtime: Runtime, world: World, navigation: Localized) -> Modules:
        """What every behaviour engine gets: the clock, the home, navigation and the senses
        (speech and understanding are added where the dialogue runs)."""
        return Modules(
            clock=runtime.clock,
            world=world,
            navigation=navigation,
            perception=self.perception,
            activity=self.activity,
        )


def build_senses(
    runtime: Runtime,
    cfg: SystemConfig,
    camera: HeadCamera,
    skeletons: Callable[[np.random.Generator], SkeletonSource],
    localization: PoseSource,
) -> Senses:
    """Perception and activity as configured, on ``camera`` and the skeleton stream
    ``skeletons`` makes from the activity's random generator: the simulator in one process,
    a feed of its topics on a deployment's edge."""
    rng_perception, rng_activity = runtime.rng.spawn(2)
    return Senses(
        build_people_finder(camera, rng_perception, cfg.perception, localization, runtime.bus),
        build_activity_recognizer(camera, skeletons(rng_activity), rng_activity, cfg.activity),
    )


@dataclass
class BehaviorLayer:
    engine: BehaviorEngine
    handlers: HandlerRegistry
    notifications: NotificationHandlerNode

    def submit(self, kind: str, payload: dict[str, Any]) -> object:
        """A request (the dialogue's ``go_to``) becomes a behaviour."""
        return self.engine.submit(self.handlers.build(kind, payload))


def build_behavior_layer(
    runtime: Runtime, cfg: SystemConfig, modules: Modules, checkpoints: bool = False
) -> BehaviorLayer:
    """The engine on ``modules`` (it keeps this very object: modules set later, before the
    runtime starts, are seen), the shipped and configured behaviours, the fall monitor on
    ``modules.activity`` (its fall notifications go through the handler below), and the
    notification handler with the residents' profiles
    (``checkpoints``: it publishes each task start, so a restarted edge can resume)."""
    engine = runtime.add(BehaviorEngine(config=cfg.behavior.engine, modules=modules))
    handlers = HandlerRegistry(engine)
    behaviors = {name: shipped_behavior(name) for name in SHIPPED_BEHAVIORS}
    behaviors.update(cfg.behavior.handlers)
    for kind, path in behaviors.items():
        if not path.is_file():
            raise ConfigError(f"behavior.handlers.{kind}: {path}: no such file")
        handlers.register(kind, yaml_handler(path), replace=True)
    residents = [p.name for p in cfg.people()]
    # A camera robot watches the people it tracks; the simulator names its residents.
    perception = modules.perception
    watch: Callable[[], list[str]] = (
        perception.people if isinstance(perception, TracksPeople) else lambda: residents
    )
    if cfg.activity.fall_detection and modules.activity is not None:
        runtime.add(FallMonitorNode(modules.activity, watch, cfg.activity.fall_period_s))
    profiles = {p.name: UserProfile(p.name, p.name.title(), p.language) for p in cfg.people()}
    notifications = runtime.add(
        NotificationHandlerNode(engine, handlers, profiles, checkpoints=checkpoints)
    )
    return BehaviorLayer(engine, handlers, notifications)


def build_system(cfg: SystemConfig, clock: Clock | None = None) -> System:
    """Everything in one runtime, seeded by ``cfg.seed``, on the robot adapter
    ``robot.adapter`` names: the simulated home by default (a :class:`SimClock`), a real
    robot's ROS 2 / NAOqi adapters otherwise (a :class:`WallClock`)."""
    adapter = adapter_type(cfg.robot.adapter)
    runtime = Runtime(clock or (SimClock() if adapter.simulated else WallClock()), seed=cfg.seed)
    if issubclass(adapter, SimAdapter):
        return _build_on_sim(cfg, runtime, adapter)
    return _build_on_robot(cfg, runtime, adapter)


def _build_on_sim(cfg: SystemConfig, runtime: Runtime, kind: type[SimAdapter]) -> System:
    if cfg.home is not None and cfg.home != cfg.sim.home:
        raise ConfigError("home: the simulated home is sim.home; set that instead")
    adapter = kind.build(runtime, cfg)
    sim = adapter.simulation
    # As an operator would on /initialpose: AMCL starts where the robot was put down, unless
    # navigation.start_place is None (global localisation from an unknown pose).
    initial_pose = None if cfg.navigation.start_place is None else sim.robot.true_pose
    navigation = _add_navigation(runtime, cfg, sim.world, initial_pose)
    senses = build_senses(runtime, cfg, sim, partial(SkeletonCamera, sim), lambda: navigation.pose)
    return _assemble(cfg, runtime, lambda: adapter, sim.world, navigation, senses, simulated=True)


def _build_on_robot(cfg: SystemConfig, runtime: Runtime, adapter: type[RobotAdapter]) -> System:
    """A real robot: its adapters, the home from ``home`` + ``navigation.map``, AMCL from
    ``navigation.start_place``, and perception and activity on its camera."""
    from amiro.system.camera import build_camera_modules

    if cfg.robot.adapter == "naoqi":
        raise ConfigError(
            "robot.adapter: naoqi alone has no laser or camera for navigation and perception: "
            "use adapter ros2 (Pepper's naoqi_driver2) with naoqi.handles beside it"
        )
    if cfg.navigation.localization == "oracle":
        raise ConfigError("navigation.localization: oracle is the simulator's true pose; use amcl")
    world = World.load(home_path(cfg), cfg.sim.resolution)
    navigation = _add_navigation(runtime, cfg, world, None)
    built = build_camera_modules(runtime, cfg, lambda: navigation.pose)
    senses = Senses(built.people, built.activity)
    # The adapter last: it connects to the robot once the rest of the config is sound.
    system = _assemble(cfg, runtime, lambda: adapter.build(runtime, cfg), world, navigation, senses)
    system.camera_people = built.people
    return system


def _add_navigation(
    runtime: Runtime, cfg: SystemConfig, world: World, initial_pose: Pose2D | None
) -> MoveToNode:
    places = {name: world.place(name) for name in world.home.places}
    navigation = runtime.add(
        build_navigation(load_map(nav_map_path(cfg)), places, cfg.navigation, initial_pose)
    )
    add_motion(runtime, cfg.navigation)
    return navigation


def add_motion(runtime: Runtime, cfg: NavigationConfig) -> None:
    """Beside MoveTo: the forward / rotate primitives, and the velocity multiplexer, the one
    writer of ``/cmd_vel`` (MoveTo and the primitives publish on its inputs)."""
    runtime.add(PrimitivesNode(speed=min(0.2, cfg.max_speed)))
    runtime.add(VelocityMuxNode())


def add_planner(
    runtime: Runtime,
    cfg: PlannerSection,
    world: World,
    engine: BehaviorEngine,
    navigation: MoveToNode,
) -> PlanExecutive:
    """The planning executive on a knowledge base of ``world``'s rooms and doors, kept up to
    date from the sensors (doors from the lidar, people from perception).  Imported here:
    the planners load unified-planning, which a system without planning does not need."""
    from amiro.behavior.planning.executive import PlanExecutive
    from amiro.behavior.planning.knowledge import KnowledgeBase
    from amiro.behavior.planning.knowledge_node import KnowledgeNode
    from amiro.behavior.planning.planner import HomePlanner
    from amiro.behavior.planning.topology import topology_from_world

    kb = KnowledgeBase(topology_from_world(world), dict(cfg.people))
    engine.modules.knowledge = kb

    def pose() -> Pose2D | None:
        return navigation.pose

    runtime.add(KnowledgeNode(kb, pose))
    planning = PlanningConfig.model_validate(cfg.model_dump(exclude={"people"}))
    return runtime.add(PlanExecutive(HomePlanner(planning), kb, engine, pose, world.room_at))


def _assemble(
    cfg: SystemConfig,
    runtime: Runtime,
    make_adapter: Callable[[], RobotAdapter],
    world: World,
    navigation: MoveToNode,
    senses: Senses,
    simulated: bool = False,
) -> System:
    """The behaviours, the smart environment and the dialogue on the robot's modules.  Only
    the simulator's residents are heard through ``dialogue.hearing``; a real robot's speech
    comes recognised from its microphone, so no audio loop is built for it."""
    rooms = list(world.home.rooms)
    modules = senses.modules(runtime, world, navigation)
    layer = build_behavior_layer(runtime, cfg, modules)
    planner = (
        None
        if cfg.behavior.planner is None
        else add_planner(runtime, cfg.behavior.planner, world, layer.engine, navigation)
    )
    sensors = runtime.add(
        SimulatedSensorsNode(rooms, cfg.environment.sensors, cfg.environment.home_id)
    )
    rules = runtime.add(RulesNode(list(cfg.environment.rules), cfg.environment.home_id))
    environment = add_environment(runtime, rooms, cfg.environment, sensors, rules)
    sources = environment_sources(runtime, environment, rooms)
    voices = household_voices(cfg.people())
    hearing = cfg.dialogue if simulated else text_hearing(cfg.dialogue)
    dialogue = build_dialogue(runtime, hearing, voices, submit=layer.submit, sources=sources)
    modules.speech, modules.nlu = dialogue.speech, dialogue.nlu
    return System(
        cfg,
        runtime,
        make_adapter(),
        world,
        navigation,
        layer.engine,
        layer.handlers,
        layer.notifications,
        sensors,
        rules,
        dialogue,
        environment,
        planner=planner,
    )
