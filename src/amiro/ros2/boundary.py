"""What the simulator shares with the edge across processes, instead of being read directly.

In one process the oracle perception and activity backends call ``sim.observe()``.  Split
over ROS 2, the robot process publishes the head camera's observations on
``/amiro/sim/observations`` and the edge keeps the latest set in an :class:`ObservationFeed`
that offers the same ``observe()``: the oracles work unchanged on either side.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from amiro.core.bus import Bus
from amiro.core.messages import Odometry, Pose2D
from amiro.core.node import Node
from amiro.sim.messages import CameraObservation

OBSERVATIONS_TOPIC = "/amiro/sim/observations"
HEARTBEAT_TOPIC = "/amiro/heartbeat"


@dataclass(frozen=True, slots=True)
class CameraObservations:
    """Everyone the head camera sees at ``stamp`` (ground truth included, as for oracles)."""

    stamp: float
    observations: tuple[CameraObservation, ...]


@dataclass(frozen=True, slots=True)
class Heartbeat:
    """A deployment process saying it is alive (``node`` is its process name)."""

    node: str
    stamp: float
    pid: int


class ObservationPublisher(Node):
    """Robot side: publishes ``observe()`` at the camera rate."""

    def __init__(self, observe: Callable[[], list[CameraObservation]], rate_hz: float = 10.0):
        super().__init__("observations")
        self.observe = observe
        self.period = 1.0 / rate_hz

    def on_start(self) -> None:
        self.pub = self.create_publisher(OBSERVATIONS_TOPIC, CameraObservations)
        self.create_timer(self.period, self._publish)

    def _publish(self) -> None:
        self.pub.publish(CameraObservations(self.now(), tuple(self.observe())))


class ObservationFeed:
    """Edge side: the latest observations received, offered as ``observe()``."""

    def __init__(self, bus: Bus) -> None:
        self.latest = CameraObservations(0.0, ())
        self.received = 0
        bus.subscribe(OBSERVATIONS_TOPIC, CameraObservations, self._on_observations, depth=1)

    def _on_observations(self, msg: CameraObservations) -> None:
        self.latest = msg
        self.received += 1

    def observe(self) -> list[CameraObservation]:
        return list(self.latest.observations)


class NavigationState:
    """Edge side, when MoveTo runs in the robot process: the pose and velocity the
    behaviour tasks read from the navigation module, fed from bridged topics instead."""

    def __init__(self, bus: Bus, pose_topic: str) -> None:
        self.pose: Pose2D | None = None
        self.velocity = (0.0, 0.0, 0.0)
        bus.subscribe(pose_topic, Pose2D, self._on_pose, depth=1)
        bus.subscribe("/odom", Odometry, self._on_odom, depth=1)

    def _on_pose(self, pose: Pose2D) -> None:
        self.pose = pose

    def _on_odom(self, msg: Odometry) -> None:
        self.velocity = (msg.twist.linear.x, msg.twist.linear.y, msg.twist.angular.z)
