"""The main settings of a deployment process, as read-only ROS 2 parameters of its node.

A ROS user inspects a running amiro process as any ROS 2 node: ``ros2 param list
/amiro_edge``, ``ros2 param describe /amiro_edge navigation.backend``.  Node names are
``amiro_<process>`` (``amiro_sim``, ``amiro_edge``, ``amiro_cloud``) unless ``ros.node_name``
says otherwise.
"""

from __future__ import annotations

from typing import Any

from amiro.deploy.config import NodeConfig
from amiro.ros2.context import RosContext
from amiro.system import SystemConfig


def parameters(node: NodeConfig, cfg: SystemConfig) -> list[tuple[str, Any, str]]:
    """(name, value, description) of each parameter; lists as string arrays (ROS 2 has
    no empty untyped array), None as an empty string."""
    return [
        ("role", node.role, "sim (the robot), edge (behaviours, perception) or cloud"),
        ("speed", float(node.speed or 0.0), "sim: simulated seconds per real second"),
        ("clock", node.clock, "edge/cloud: follow the robot's /clock, or wall time"),
        ("serve_actions", [*node.serve_actions, ""], "ROS 2 actions served here (+ '')"),
        ("call_actions", [*node.call_actions, ""], "ROS 2 actions called from here (+ '')"),
        ("action_timeout_s", float(node.action_timeout_s), "a goal with no server aborts"),
        ("heartbeat_s", float(node.heartbeat_s), "period of /amiro/heartbeat"),
        ("navigation.backend", cfg.navigation.backend, "amiro, or nav2 (the robot's Nav2)"),
        ("navigation.localization", cfg.navigation.localization, "amcl or oracle"),
        ("navigation.max_speed", float(cfg.navigation.max_speed), "m/s"),
        ("perception.backend", cfg.perception.backend, "what finds people"),
        ("activity.backend", cfg.activity.backend, "what recognises activities"),
    ]


def declare_parameters(ros: RosContext, node: NodeConfig, cfg: SystemConfig) -> None:
    for name, value, description in parameters(node, cfg):
        ros.declare(name, value, description)
