"""What each deployment role runs, built from the same SystemConfig as the embedded system.

The split follows the paper's section 3.1: only bus topics cross between roles (see
:mod:`amiro.deploy.config` for which), so any role can move to another process or machine.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import amiro.behavior.tasks  # noqa: F401 - registers the task types
from amiro.core import names
from amiro.core.gridmap import load_map
from amiro.core.messages import OccupancyGrid
from amiro.core.node import Node
from amiro.core.runtime import Runtime
from amiro.deploy.behaviors import BehaviorActionServer
from amiro.deploy.boundary import HeadSensorsFeed, HeadSensorsPublisher, NavigationState
from amiro.deploy.cloud import add_cloud_services, pose_topic
from amiro.deploy.config import NodeConfig
from amiro.deploy.dialogue import RemoteUnderstanding
from amiro.deploy.health import HeartbeatNode, NotificationLedger, Watchdog
from amiro.deploy.ledger_store import LedgerStore
from amiro.deploy.nav2 import uses_nav2
from amiro.deploy.people import TrackedPeoplePublisher, finder_tracker
from amiro.deploy.sim_camera import SimCameraNode
from amiro.deploy.task_actions import TASK_ACTIONS, TaskActionServer
from amiro.deploy.tf import MapOdomNode, robot_frames
from amiro.dialogue.output import BusSpeechOutput
from amiro.dialogue.ports import Understanding
from amiro.dialogue.profiles import household_voices
from amiro.dialogue.stack import (
    add_microphone,
    add_recognizer,
    build_understanding,
    text_hearing,
)
from amiro.environment.rules import RulesNode
from amiro.environment.simulated import SimulatedSensorsNode
from amiro.home.world import World, default_home_path
from amiro.navigation.move_to import MoveToNode
from amiro.navigation.stack import build_navigation
from amiro.perception.stack import SimPeopleFinder
from amiro.robot.camera import CameraParams
from amiro.sim.simulator import build_sim
from amiro.sim.skeletons import SkeletonCamera
from amiro.system import (
    BehaviorLayer,
    Senses,
    SystemConfig,
    add_motion,
    build_behavior_layer,
    build_senses,
    home_path,
    nav_map_path,
)

# What the edge's report calls each perception backend.
PERCEPTION_NAMES = {"sim": "sim-detector"}


class MapPublisher(Node):
    """Publishes the static map once on ``/map`` (latched on the ROS side)."""

    def __init__(self, grid: OccupancyGrid) -> None:
        super().__init__("map")
        self.grid = grid

    def on_start(self) -> None:
        self.create_publisher(names.MAP, OccupancyGrid).publish(self.grid)


@dataclass
class RoleParts:
    """What a role built, as far as the process needs to know: a summary for its report."""

    summary: Callable[[], dict[str, Any]]
    close: Callable[[], None] = lambda: None  # after the runtime stops (a robot's adapters)


def add_navigation(runtime: Runtime, cfg: SystemConfig, world: World) -> MoveToNode:
    """MoveTo, the primitives and the velocity mux (so ``/cmd_vel`` is written where
    navigation runs), and map -> odom on /tf."""
    places = {name: world.place(name) for name in world.home.places}
    runtime.add(MapOdomNode(pose_topic(cfg)))  # map -> odom on /tf, where localisation runs
    navigation = runtime.add(build_navigation(load_map(nav_map_path(cfg)), places, cfg.navigation))
    add_motion(runtime, cfg.navigation)
    return navigation


def build_sim_role(
    runtime: Runtime, process: str, node: NodeConfig, cfg: SystemConfig
) -> RoleParts:
    sim = build_sim(runtime, cfg.sim)
    if {names.MOVE_TO, names.NAVIGATE_TO_POSE} & set(node.serve_actions):
        # navigation next to the robot, driven remotely (by amiro's edge, or any Nav2 client)
        add_navigation(runtime, cfg, sim.world)
    (rng_skeletons,) = runtime.rng.spawn(1)
    rendered = node.camera is not None
    runtime.add(
        HeadSensorsPublisher(sim, SkeletonCamera(sim, rng_skeletons), publish_info=not rendered)
    )
    if node.camera is not None:  # pixels for a real-robot stack (perception.backend camera)
        runtime.add(SimCameraNode(sim, node.camera))
    grid = load_map(nav_map_path(cfg)).to_occupancy_grid(0.0)
    runtime.add(MapPublisher(grid))
    runtime.add(robot_frames(sim))  # /tf_static mounts and the head camera on /tf
    runtime.add(HeartbeatNode(process, node.heartbeat_s))
    residents = household_voices(cfg.people())
    microphone = add_microphone(runtime, cfg.dialogue, residents) if node.hear_audio else None

    def summary() -> dict[str, Any]:
        pose = sim.robot.true_pose
        voiced = {} if microphone is None else {"voiced": [t for t, _ in microphone.voiced]}
        return {
            "pose": [round(pose.x, 3), round(pose.y, 3), round(pose.theta, 3)],
            "collisions": sim.robot.collisions,
            "replies": len(sim.residents.replies),
            **voiced,
        }

    return RoleParts(summary)


def build_edge_role(
    runtime: Runtime, process: str, node: NodeConfig, cfg: SystemConfig
) -> RoleParts:
    world = World.load(cfg.sim.home or default_home_path(), cfg.sim.resolution)
    navigation: MoveToNode | NavigationState = (
        NavigationState(runtime.bus, pose_topic(cfg))
        if names.MOVE_TO in node.call_actions or uses_nav2(cfg)
        else add_navigation(runtime, cfg, world)
    )
    feed = HeadSensorsFeed(
        runtime.bus,
        (cfg.sim.camera.height, CameraParams().forward),
        tuple(p.name for p in cfg.people()),
        lambda: navigation.pose,
        cfg.sim.skeletons.pitch_deg,
    )
    senses = build_senses(runtime, cfg, feed, lambda _rng: feed, feed.robot_pose)
    tracker = finder_tracker(senses.perception)
    if tracker is not None:  # the cloud's dashboard shows whom perception tracks
        runtime.add(TrackedPeoplePublisher(tracker))
    layer = edge_behaviors(runtime, process, node, cfg, world, navigation, senses)
    heard = hearing(runtime, node, cfg)

    def summary() -> dict[str, Any]:
        return {
            "runs": [{"id": r.id, "outcome": r.outcome} for r in layer.engine.runs.values()],
            **senses_report(cfg, senses),
            "received": dict(feed.received),
            **heard(),
        }

    return RoleParts(summary)


def edge_behaviors(
    runtime: Runtime,
    process: str,
    node: NodeConfig,
    cfg: SystemConfig,
    world: World,
    navigation: MoveToNode | NavigationState,
    senses: Senses,
) -> BehaviorLayer:
    """The edge's behaviour engine on its modules, the behaviour action if served, and the
    heartbeat: the same on the simulator's topics and on a real robot's adapters."""
    residents = household_voices(cfg.people())
    nlu: Understanding = (
        RemoteUnderstanding(runtime.bus)
        if names.UNDERSTAND in node.call_services
        else build_understanding(text_hearing(cfg.dialogue), residents, runtime.clock)[1]
    )
    modules = senses.modules(runtime, world, navigation)
    modules.speech = BusSpeechOutput(runtime.bus, cfg.dialogue.words_per_second)
    modules.nlu = nlu
    layer = build_behavior_layer(runtime, cfg, modules, checkpoints=True)
    if names.BEHAVIOR_RUN in node.serve_actions:  # the cloud's dialogue and dashboard ask
        runtime.add(BehaviorActionServer(layer.engine, layer.handlers))
    for action in TASK_ACTIONS:  # Search and RecognizeActivity as typed actions
        if action.name in node.serve_actions:
            runtime.add(TaskActionServer(layer.engine, action))
    runtime.add(HeartbeatNode(process, node.heartbeat_s))
    return layer


def hearing(runtime: Runtime, node: NodeConfig, cfg: SystemConfig) -> Callable[[], dict[str, Any]]:
    """The recogniser of ``/amiro/audio`` when this process hears audio, and its report."""
    if not node.hear_audio:
        return dict
    recognizer = add_recognizer(runtime, cfg.dialogue, household_voices(cfg.people()))
    return lambda: {"recognized": list(recognizer.heard)}


def senses_report(cfg: SystemConfig, senses: Senses) -> dict[str, Any]:
    """Which perception and activity backends ran, and how many people they placed."""
    finder = senses.perception
    return {
        "perception": PERCEPTION_NAMES.get(cfg.perception.backend, cfg.perception.backend),
        "activity": cfg.activity.backend,
        "people_estimates": finder.estimates if isinstance(finder, SimPeopleFinder) else None,
    }


def build_cloud_role(
    runtime: Runtime, process: str, node: NodeConfig, cfg: SystemConfig
) -> RoleParts:
    home = World.load(home_path(cfg), cfg.sim.resolution).home
    env = cfg.environment
    sensors = runtime.add(SimulatedSensorsNode(list(home.rooms), env.sensors, env.home_id))
    rules = runtime.add(RulesNode(list(env.rules), env.home_id))
    store = None if node.ledger_path is None else LedgerStore(node.ledger_path)
    ledger = runtime.add(NotificationLedger(store=store))
    watchdog = runtime.add(Watchdog(dict(node.watch)))
    services = add_cloud_services(runtime, node, cfg, home, sensors, rules)
    heard = hearing(runtime, node, cfg)

    def summary() -> dict[str, Any]:
        return {
            **heard(),
            "pending_notifications": sorted(ledger.pending),
            "redelivered": ledger.resent,
            **ledger.persistence(),
            "lost": {name: peer.lost for name, peer in watchdog.peers.items()},
            **services.summary(),
        }

    return RoleParts(summary)


BUILDERS = {"sim": build_sim_role, "edge": build_edge_role, "cloud": build_cloud_role}
