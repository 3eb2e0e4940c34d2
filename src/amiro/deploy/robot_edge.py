"""The edge of a split deployment on a real ROS 2 robot (``robot.adapter: ros2``).

The robot process is then the robot's own driver (naoqi_driver2, a base's bringup, or
``amiro sim --ros2`` standing in for one): the edge reaches it through the same
:func:`amiro.robot.build.build_robot` adapters as the embedded system, with the profile's
topic names, frames and velocity limits, and runs navigation on its /scan and /odom and
perception and activity on its camera (:func:`build_camera_modules`).  The adapters join
the process's own ROS domain (its ``ros:`` section), so one setting places the edge.
"""

from __future__ import annotations

from typing import Any

from amiro.core.config import ConfigError
from amiro.core.runtime import Runtime
from amiro.deploy.boundary import NavigationState
from amiro.deploy.cloud import pose_topic
from amiro.deploy.config import NodeConfig
from amiro.deploy.nav2 import uses_nav2
from amiro.deploy.people import TrackedPeoplePublisher
from amiro.deploy.roles import RoleParts, add_navigation, edge_behaviors
from amiro.home.world import World
from amiro.navigation.move_to import MoveToNode
from amiro.robot.build import build_robot
from amiro.robot.config import RobotConfig
from amiro.ros2.context import RosSection
from amiro.system import Senses, SystemConfig, home_path
from amiro.system.camera import build_camera_modules


def robot_on_process_domain(robot: RobotConfig, node: NodeConfig, process: str) -> RobotConfig:
    """``robot`` with the process's ROS domain and discovery range (its adapters' node is
    ``<process node>_robot``); a different ``robot.ros`` would split the edge in two."""
    if robot.ros != RosSection():
        raise ConfigError(
            "robot.ros: on a deployment's edge the robot adapters use the process's ros: "
            "section (domain_id, localhost_only); set them there"
        )
    ros = node.ros.model_copy(update={"node_name": f"{node.ros_node_name(process)}_robot"})
    return robot.model_copy(update={"ros": ros})


def build_robot_edge(
    runtime: Runtime, process: str, node: NodeConfig, cfg: SystemConfig
) -> RoleParts:
    if cfg.robot.adapter != "ros2":
        raise ConfigError(
            f"robot.adapter: {cfg.robot.adapter}: a deployment's edge drives a robot through "
            "its ROS 2 driver (adapter ros2, with naoqi.handles beside it on Pepper)"
        )
    if cfg.navigation.localization == "oracle":
        raise ConfigError("navigation.localization: oracle is the simulator's true pose; use amcl")
    robot_cfg = robot_on_process_domain(cfg.robot, node, process)
    world = World.load(home_path(cfg), cfg.sim.resolution)
    navigation: MoveToNode | NavigationState = (
        NavigationState(runtime.bus, pose_topic(cfg))  # MoveTo is the robot's Nav2
        if uses_nav2(cfg)
        else add_navigation(runtime, cfg, world)
    )
    camera = build_camera_modules(runtime, cfg, lambda: navigation.pose)
    senses = Senses(camera.people, camera.activity)
    runtime.add(TrackedPeoplePublisher(camera.people.tracker))  # the cloud's dashboard
    layer = edge_behaviors(runtime, process, node, cfg, world, navigation, senses)
    robot = build_robot(runtime, robot_cfg)  # last: connects once the config is sound

    def summary() -> dict[str, Any]:
        pose = navigation.pose
        return {
            "runs": [{"id": r.id, "outcome": r.outcome} for r in layer.engine.runs.values()],
            "perception": cfg.perception.backend,
            "activity": cfg.activity.backend,
            "robot": {"profile": robot.profile.name, **robot.stats()},
            "pose_estimate": None
            if pose is None
            else [round(pose.x, 3), round(pose.y, 3), round(pose.theta, 3)],
            "people_tracked": sum(t.confirmed for t in camera.people.tracker.tracks),
        }

    return RoleParts(summary, robot.close)
