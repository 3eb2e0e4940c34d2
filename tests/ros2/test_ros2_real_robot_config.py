"""The shipped real-robot deployment and the edge's robot options, without starting ROS 2."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

import pytest

from amiro.core import names
from amiro.core.config import ConfigError, load
from amiro.deploy.config import NodeConfig, RosSection
from amiro.deploy.launch import load_deployment
from amiro.deploy.robot_edge import robot_on_process_domain
from amiro.robot.config import RobotConfig
from amiro.system import SystemConfig

SHIPPED = Path(str(resources.files("amiro").joinpath("data/deployments/robot-ros2.yaml")))
DRIVER_TOPICS = {names.SCAN, names.ODOM, names.CMD_VEL, names.IMAGE, names.HEAD_CMD, names.TF}


def test_the_shipped_deployment_runs_edge_and_cloud_on_wall_time() -> None:
    deployment = load_deployment(SHIPPED)
    nodes = {p.name: load(NodeConfig, p.config) for p in deployment.processes}
    assert {name: (n.role, n.clock) for name, n in nodes.items()} == {
        "edge": ("edge", "wall"),
        "cloud": ("cloud", "wall"),
    }
    for node in nodes.values():
        assert node.system is not None
        system = load(SystemConfig, SHIPPED.parent / node.system)
        assert system.robot.adapter == "ros2" and system.perception.backend == "camera"


def test_a_robot_edge_leaves_the_drivers_topics_to_its_adapter() -> None:
    edge = NodeConfig(role="edge")
    assert not DRIVER_TOPICS & {*edge.topics_out(robot=True), *edge.topics_in(robot=True)}
    assert {"/amiro/events", "/amiro/heartbeat", "/amiro/people"} <= set(
        edge.topics_out(robot=True)
    )
    assert "/amiro/notifications" in edge.topics_in(robot=True)
    assert names.CMD_VEL in edge.topics_out()  # on the simulator's topics, the bridge drives


def test_the_robot_adapters_join_the_process_domain() -> None:
    node = NodeConfig(role="edge", ros=RosSection(domain_id=7, localhost_only=False))
    robot = robot_on_process_domain(RobotConfig(adapter="ros2"), node, "edge")
    assert robot.ros == RosSection(domain_id=7, localhost_only=False, node_name="amiro_edge_robot")
    own = RobotConfig(adapter="ros2", ros=RosSection(domain_id=3))
    with pytest.raises(ConfigError, match="process's ros: section"):
        robot_on_process_domain(own, node, "edge")


def test_following_the_sim_clock_stays_the_default() -> None:
    assert NodeConfig(role="cloud").clock == "follow"
