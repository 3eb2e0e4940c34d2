"""One rclpy participant per process: its own context, node and executor.

rclpy is imported here only, and lazily, so amiro without the ``ros2`` extra still imports.
Every rclpy callback runs inside :meth:`RosContext.spin`, called from the runtime's single
thread, so callbacks may publish on the bus without locks.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

from pydantic import Field

from amiro.core.config import ConfigError, Section
from amiro.ros2 import env as ros_env
from amiro.ros2.types import RclpyTypes


class RosSection(Section):
    """Where a process meets ROS 2: its DDS domain, loopback only or not, its node name."""

    domain_id: int | None = Field(default=None, ge=0, le=ros_env.MAX_DOMAIN_ID)
    localhost_only: bool = True
    node_name: str | None = Field(default=None, description="default: amiro_<process name>")


def _rclpy() -> Any:
    try:
        import rclpy
    except ImportError:
        raise ConfigError(
            "ROS 2 needs rclpy: pip install 'amiro[ros2]' (ros-jazzy-rclpy and messages)"
        ) from None
    return rclpy


class RosContext:
    """A ROS 2 node in its own context (several may live in one process, e.g. in tests)."""

    def __init__(
        self, node_name: str, domain_id: int | None = None, localhost_only: bool = True
    ) -> None:
        ros_env.apply(ros_env.ros_environment(domain_id, localhost_only))
        rclpy = _rclpy()
        from rclpy.context import Context
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.signals import SignalHandlerOptions

        self.types = RclpyTypes()
        self.context = Context()
        # amiro handles SIGINT/SIGTERM itself, to stop its nodes before rclpy goes down.
        rclpy.init(
            context=self.context,
            domain_id=domain_id,
            signal_handler_options=SignalHandlerOptions.NO,
        )
        self.node = rclpy.create_node(node_name, context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self.callbacks = 0  # rclpy callbacks run so far: tells spin when the queue is empty

    def qos(self, depth: int = 10, latched: bool = False) -> Any:
        from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

        return QoSProfile(  # type: ignore[no-untyped-call]
            history=HistoryPolicy.KEEP_LAST,
            depth=depth,
            reliability=ReliabilityPolicy.RELIABLE,
            durability=(DurabilityPolicy.TRANSIENT_LOCAL if latched else DurabilityPolicy.VOLATILE),
        )

    def publisher(self, type_name: str, topic: str, depth: int = 10, latched: bool = False) -> Any:
        cls = self.types.message_class(type_name)
        return self.node.create_publisher(cls, topic, self.qos(depth, latched))

    def subscribe(
        self,
        type_name: str,
        topic: str,
        callback: Callable[[Any], None],
        depth: int = 10,
        latched: bool = False,
    ) -> Any:
        def counted(msg: Any) -> None:
            self.callbacks += 1
            callback(msg)

        cls = self.types.message_class(type_name)
        return self.node.create_subscription(cls, topic, counted, self.qos(depth, latched))

    def spin(self, timeout_s: float = 0.0, max_callbacks: int = 10_000) -> int:
        """Run pending callbacks (waiting up to ``timeout_s`` for the first); returns how many."""
        start = self.callbacks
        self.executor.spin_once(timeout_sec=timeout_s)
        while self.callbacks - start < max_callbacks:
            before = self.callbacks
            self.executor.spin_once(timeout_sec=0.0)
            if self.callbacks == before:
                break
        return self.callbacks - start

    def declare(self, name: str, value: Any, description: str) -> None:
        """A read-only ROS 2 parameter: what this process runs with, for ``ros2 param``
        (``list``, ``get``, ``describe``); changing a setting means restarting it."""
        from rcl_interfaces.msg import ParameterDescriptor

        descriptor = ParameterDescriptor(description=description, read_only=True)
        self.node.declare_parameter(name, value, descriptor)

    def node_names(self) -> list[str]:
        return [str(n) for n in self.node.get_node_names()]

    def wait_for_nodes(
        self, names: list[str], timeout_s: float, cancelled: Callable[[], bool] = lambda: False
    ) -> list[str]:
        """Wait (wall time) until these ROS nodes are on the graph; returns the missing ones."""
        deadline = time.monotonic() + timeout_s
        missing = [n for n in names if n not in self.node_names()]
        while missing and time.monotonic() < deadline and not cancelled():
            self.spin(0.1)
            missing = [n for n in names if n not in self.node_names()]
        return missing

    def close(self) -> None:
        rclpy = _rclpy()
        self.executor.shutdown(timeout_sec=1.0)
        self.node.destroy_node()
        if self.context.ok():
            rclpy.shutdown(context=self.context)
