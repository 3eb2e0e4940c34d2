"""What each deployment role runs, built from the same SystemConfig as the embedded system.

The split follows the paper's section 3.1: only bus topics cross between roles (see
:mod:`amiro.ros2.config` for which), so any role can move to another process or machine.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, cast

import amiro.behavior.tasks  # noqa: F401 - registers the task types
from amiro.activity.oracle import OracleActivityRecognizer
from amiro.behavior.engine import BehaviorEngine
from amiro.behavior.handlers import HandlerRegistry, yaml_handler
from amiro.behavior.notifications import NotificationHandlerNode, UserProfile
from amiro.core.config import ConfigError
from amiro.core.gridmap import load_map
from amiro.core.messages import OccupancyGrid
from amiro.core.node import Node
from amiro.core.runtime import Runtime
from amiro.dialogue.oracle import OracleUnderstanding
from amiro.dialogue.output import BusSpeechOutput
from amiro.dialogue.ports import Understanding
from amiro.dialogue.profiles import SpeakerProfile
from amiro.dialogue.stack import build_dialogue
from amiro.environment.rules import RulesNode
from amiro.environment.simulated import SimulatedSensorsNode
from amiro.navigation.localization import GROUND_TRUTH_TOPIC, LOCALIZATION_TOPIC
from amiro.navigation.move_to import MOVE_TO_ACTION, MoveToNode
from amiro.navigation.stack import build_navigation
from amiro.perception.oracle import OraclePeopleFinder
from amiro.ros2.boundary import NavigationState, ObservationFeed, ObservationPublisher
from amiro.ros2.config import NodeConfig
from amiro.ros2.dialogue import UNDERSTAND_SERVICE, RemoteUnderstanding, UnderstandingService
from amiro.ros2.health import HeartbeatNode, NotificationLedger, Watchdog
from amiro.sim.simulator import Simulation, build_sim
from amiro.sim.world import World, default_home_path
from amiro.system import SystemConfig, nav_map_path, shipped_behavior


class MapPublisher(Node):
    """Publishes the static map once on ``/map`` (latched on the ROS side)."""

    def __init__(self, grid: OccupancyGrid) -> None:
        super().__init__("map")
        self.grid = grid

    def on_start(self) -> None:
        self.create_publisher("/map", OccupancyGrid).publish(self.grid)


@dataclass
class RoleParts:
    """What a role built, as far as the process needs to know: a summary for its report."""

    summary: Callable[[], dict[str, Any]]


def _navigation(runtime: Runtime, cfg: SystemConfig, world: World) -> MoveToNode:
    places = {name: world.place(name) for name in world.home.places}
    return runtime.add(build_navigation(load_map(nav_map_path(cfg)), places, cfg.navigation))


def _pose_topic(cfg: SystemConfig) -> str:
    """Where the robot's pose estimate is published (what MoveTo itself listens to)."""
    return GROUND_TRUTH_TOPIC if cfg.navigation.localization == "oracle" else LOCALIZATION_TOPIC


def build_sim_role(
    runtime: Runtime, process: str, node: NodeConfig, cfg: SystemConfig
) -> RoleParts:
    sim = build_sim(runtime, cfg.sim)
    if MOVE_TO_ACTION in node.serve_actions:  # navigation next to the robot, driven remotely
        _navigation(runtime, cfg, sim.world)
    runtime.add(ObservationPublisher(sim.observe))
    grid = load_map(nav_map_path(cfg)).to_occupancy_grid(0.0)
    runtime.add(MapPublisher(grid))
    runtime.add(HeartbeatNode(process, node.heartbeat_s))

    def summary() -> dict[str, Any]:
        pose = sim.robot.true_pose
        return {
            "pose": [round(pose.x, 3), round(pose.y, 3), round(pose.theta, 3)],
            "collisions": sim.robot.collisions,
            "replies": len(sim.residents.replies),
        }

    return RoleParts(summary)


def build_edge_role(
    runtime: Runtime, process: str, node: NodeConfig, cfg: SystemConfig
) -> RoleParts:
    world = World.load(cfg.sim.home or default_home_path(), cfg.sim.resolution)
    navigation: MoveToNode | NavigationState = (
        NavigationState(runtime.bus, _pose_topic(cfg))
        if MOVE_TO_ACTION in node.call_actions
        else _navigation(runtime, cfg, world)
    )
    feed = ObservationFeed(runtime.bus)
    remote_sim = cast(Simulation, feed)  # the oracles only call observe()
    nlu: Understanding = (
        RemoteUnderstanding(runtime.bus)
        if UNDERSTAND_SERVICE in node.call_services
        else OracleUnderstanding()
    )
    rng_perception, rng_activity = runtime.rng.spawn(2)
    modules = {
        "clock": runtime.clock,
        "world": world,
        "navigation": navigation,
        "perception": OraclePeopleFinder(
            remote_sim, rng_perception, cfg.perception.position_noise_m
        ),
        "activity": OracleActivityRecognizer(remote_sim, rng_activity, cfg.activity.accuracy),
        "speech": BusSpeechOutput(runtime.bus, cfg.dialogue.words_per_second),
        "nlu": nlu,
    }
    engine = runtime.add(BehaviorEngine(config=cfg.behavior.engine, modules=modules))
    handlers = HandlerRegistry(engine)
    for kind, path in {"hydration": shipped_behavior("hydration"), **cfg.behavior.handlers}.items():
        if not path.is_file():
            raise ConfigError(f"behavior.handlers.{kind}: {path}: no such file")
        handlers.register(kind, yaml_handler(path), replace=True)
    profiles = {r.name: UserProfile(r.name, r.name.title(), r.language) for r in cfg.sim.residents}
    runtime.add(NotificationHandlerNode(engine, handlers, profiles))
    runtime.add(HeartbeatNode(process, node.heartbeat_s))

    def summary() -> dict[str, Any]:
        return {
            "runs": [{"id": r.id, "outcome": r.outcome} for r in engine.runs.values()],
            "observations_received": feed.received,
        }

    return RoleParts(summary)


def _dialogue_service(runtime: Runtime, cfg: SystemConfig) -> UnderstandingService:
    """The dialogue stack (NLU, dialogue manager, TTS if configured) with its understanding
    offered to the edge's Listen tasks."""
    voices = {
        r.name: SpeakerProfile.model_validate({"lang": r.language}) for r in cfg.sim.residents
    }
    dialogue = build_dialogue(runtime, cfg.dialogue, voices)
    return runtime.add(UnderstandingService(dialogue.nlu))


def build_cloud_role(
    runtime: Runtime, process: str, node: NodeConfig, cfg: SystemConfig
) -> RoleParts:
    world_rooms = list(
        World.load(cfg.sim.home or default_home_path(), cfg.sim.resolution).home.rooms
    )
    env = cfg.environment
    runtime.add(SimulatedSensorsNode(world_rooms, env.sensors, env.home_id))
    runtime.add(RulesNode(list(env.rules), env.home_id))
    ledger = runtime.add(NotificationLedger())
    watchdog = runtime.add(Watchdog(dict(node.watch)))
    understanding = (
        _dialogue_service(runtime, cfg) if UNDERSTAND_SERVICE in node.serve_services else None
    )

    def summary() -> dict[str, Any]:
        report: dict[str, Any] = {
            "pending_notifications": sorted(ledger.pending),
            "redelivered": ledger.resent,
            "lost": {name: peer.lost for name, peer in watchdog.peers.items()},
        }
        if understanding is not None:
            report["understood"] = [
                {"intent": u.intent, "confidence": round(u.confidence, 3)}
                for u in understanding.answered
            ]
        return report

    return RoleParts(summary)


BUILDERS = {"sim": build_sim_role, "edge": build_edge_role, "cloud": build_cloud_role}
