"""Forward and rotate primitives: short relative moves on odometry, as bus actions.

Behaviours need simple moves that no map or plan is worth ("turn to face the person",
"step back 0.3 m").  Both run on odometry (relative moves, where it is accurate), stop at
once on cancel, hold still while the emergency stop is on, and a forward move fails with
``blocked`` when the lidar sees something within ``clearance`` ahead (or behind, going back).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from amiro.core import names
from amiro.core.bus import ActionServer, GoalHandle
from amiro.core.geometry import wrap_angle
from amiro.core.messages import LaserScan, Odometry, Pose2D, String, Twist
from amiro.core.node import Node
from amiro.core.safety import estop_engaged
from amiro.navigation.poses import between


@dataclass(frozen=True)
class ForwardGoal:
    distance: float  # metres along the heading at the start; negative: backwards
    speed: float | None = None  # m/s, at most the node's speed; None: the node's speed


@dataclass(frozen=True)
class RotateGoal:
    angle: float  # radians, counter-clockwise positive; may exceed a half turn


@dataclass(frozen=True)
class PrimitiveFeedback:
    remaining: float  # metres or radians


@dataclass(frozen=True)
class PrimitiveResult:
    success: bool
    reason: str  # "done", "blocked", "canceled", "no_odometry", "preempted_by_new_goal"
    achieved: float = 0.0  # metres or radians actually moved


Handle = GoalHandle[Any, PrimitiveFeedback, PrimitiveResult]


@dataclass
class _Motion:
    handle: Handle
    rotate: bool
    target: float
    start: Pose2D
    last: Pose2D
    limit: float  # m/s or rad/s
    turned: float = 0.0

    def achieved(self) -> float:
        return self.turned if self.rotate else between(self.start, self.last).x


def _finite(value: object) -> bool:
    return isinstance(value, int | float) and math.isfinite(value)


def valid_goal(goal: Any, rotate: bool) -> bool:
    """A finite distance or angle, and a positive speed if one is given."""
    value = goal.angle if rotate else goal.distance
    speed = None if rotate else goal.speed
    return _finite(value) and (speed is None or (_finite(speed) and speed > 0.0))


class _Server(ActionServer[Any, PrimitiveFeedback, PrimitiveResult]):
    def __init__(self, node: PrimitivesNode, rotate: bool) -> None:
        self.node = node
        self.rotate = rotate

    def accept(self, goal: Any) -> bool:
        return valid_goal(goal, self.rotate)

    def execute(self, handle: Handle) -> None:
        self.node.begin(handle, self.rotate)

    def cancel(self, handle: Handle) -> None:
        self.node.end(handle, False, "canceled")

    def canceled_result(self, handle: Handle) -> PrimitiveResult:
        return self.node.result_for(handle, False, "canceled")


class PrimitivesNode(Node):
    """Serves ``names.FORWARD`` and ``names.ROTATE`` (one motion at a time)."""

    def __init__(
        self,
        speed: float = 0.2,
        turn_rate: float = 0.6,
        clearance: float = 0.45,
        period: float = 0.05,
    ) -> None:
        super().__init__("primitives")
        self.speed, self.turn_rate, self.clearance, self.period = (
            speed,
            turn_rate,
            clearance,
            period,
        )
        self.odom: Pose2D | None = None
        self.scan: LaserScan | None = None
        self.emergency_stop = False
        self.active: _Motion | None = None

    def on_start(self) -> None:
        self.cmd_pub = self.create_publisher(names.CMD_VEL_PRIMITIVES, Twist)  # the mux's input
        self.create_subscription(names.ODOM, Odometry, self._on_odom, depth=1)
        self.create_subscription(names.SCAN, LaserScan, self._on_scan, depth=1)
        self.create_subscription(names.EMERGENCY_STOP, String, self._on_estop, depth=10)
        self.create_action_server(names.FORWARD, _Server(self, rotate=False))
        self.create_action_server(names.ROTATE, _Server(self, rotate=True))
        self.create_timer(self.period, self._control)

    def _on_odom(self, msg: Odometry) -> None:
        self.odom = msg.pose.to_pose2d()

    def _on_scan(self, scan: LaserScan) -> None:
        self.scan = scan

    def _on_estop(self, msg: String) -> None:
        """The mux stops the base; here a motion only waits for the release."""
        self.emergency_stop = estop_engaged(msg.data)

    def begin(self, handle: Handle, rotate: bool) -> None:
        if self.active is not None:
            self.end(self.active.handle, False, "preempted_by_new_goal")
        if self.odom is None:
            handle.abort(PrimitiveResult(False, "no_odometry"))
            return
        goal = handle.goal
        target = float(goal.angle if rotate else goal.distance)
        limit = self.turn_rate if rotate else min(self.speed, goal.speed or self.speed)
        self.active = _Motion(handle, rotate, target, self.odom, self.odom, limit)

    def result_for(self, handle: Handle, success: bool, reason: str) -> PrimitiveResult:
        active = self.active
        achieved = active.achieved() if active is not None and active.handle is handle else 0.0
        return PrimitiveResult(success, reason, achieved)

    def end(self, handle: Handle, success: bool, reason: str) -> None:
        result = self.result_for(handle, success, reason)
        if self.active is not None and self.active.handle is handle:
            self.active = None
            self.cmd_pub.publish(Twist())
        if success:
            handle.succeed(result)
        elif reason == "canceled":
            handle.canceled(result)
        else:
            handle.abort(result)

    def _control(self) -> None:
        motion = self.active
        if motion is None or self.odom is None:
            return
        motion.turned += wrap_angle(self.odom.theta - motion.last.theta)
        motion.last = self.odom
        remaining = motion.target - motion.achieved()
        if abs(remaining) < (0.01 if motion.rotate else 0.005):
            self.end(motion.handle, True, "done")
            return
        if self.emergency_stop:
            self.cmd_pub.publish(Twist())
            return
        if not motion.rotate and self._blocked(backwards=remaining < 0):
            self.end(motion.handle, False, "blocked")
            return
        limit = motion.limit
        # slow down over the last stretch (about 2 control periods of travel per unit)
        value = math.copysign(min(limit, max(0.05 * limit, 2.0 * abs(remaining))), remaining)
        self.cmd_pub.publish(
            Twist.planar(0.0, 0.0, value) if motion.rotate else Twist.planar(value, 0.0, 0.0)
        )
        motion.handle.publish_feedback(PrimitiveFeedback(abs(remaining)))

    def _blocked(self, backwards: bool) -> bool:
        """Any lidar return within ``clearance`` in a 70-degree cone along the motion."""
        scan = self.scan
        if scan is None:
            return False
        heading = math.pi if backwards else 0.0
        angles = scan.angles()
        ranges = np.asarray(scan.ranges)
        cone = np.abs(
            np.arctan2(np.sin(angles - heading), np.cos(angles - heading))
        ) < math.radians(35)
        near = np.isfinite(ranges) & (ranges > 0.0) & (ranges < self.clearance)
        return bool(np.any(cone & near))
