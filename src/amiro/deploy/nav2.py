"""``navigation.backend: nav2``: MoveTo and the primitives on the edge's bus are clients of the
robot's own Nav2.

MoveTo goals go to ``/navigate_to_pose`` (places resolved to their pose, a person to a pose
``approach`` metres short of her); Nav2's feedback becomes MoveTo's, its result codes
MoveTo's failure reasons (:func:`amiro.deploy.codecs.nav2_reason`), and cancelling a
MoveTo cancels the Nav2 goal.  The forward and rotate primitives go to Nav2's behaviour
server where the robot offers it (``/drive_on_heading``, ``/backup``, ``/spin``), else to
``/navigate_to_pose`` with the pose they would reach.  The behaviour tasks read the robot's
pose from the bridged localisation topic, as when MoveTo runs in another amiro process.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from amiro.core import names
from amiro.core.bus import ActionServer, GoalHandle, GoalStatus
from amiro.core.messages import Pose2D
from amiro.core.node import Node
from amiro.core.runtime import Runtime
from amiro.deploy.boundary import NavigationState
from amiro.deploy.cloud import pose_topic
from amiro.deploy.codecs import NavigateToPoseCodec
from amiro.deploy.nav2_behaviors import BackUpCodec, DriveOnHeadingCodec, SpinCodec
from amiro.home.world import World
from amiro.navigation.move_to import MoveToGoal, MoveToResult
from amiro.navigation.primitives import PrimitiveFeedback, PrimitiveResult, valid_goal
from amiro.ros2.actions import RemoteActionServer
from amiro.ros2.context import RosContext
from amiro.system import SystemConfig

Handle = GoalHandle[Any, PrimitiveFeedback, PrimitiveResult]


def uses_nav2(cfg: SystemConfig) -> bool:
    return cfg.navigation.backend == "nav2"


@dataclass
class _Motion:
    handle: Handle
    amount: float  # metres or radians asked for (signed)
    inner: GoalHandle[Any, Any, Any] | None = None
    done_so_far: float = 0.0  # metres or radians Nav2 reports travelled
    via_pose: bool = False  # the fallback: a NavigateToPose goal


class _Primitive(ActionServer[Any, PrimitiveFeedback, PrimitiveResult]):
    def __init__(self, owner: Nav2Primitives, rotate: bool) -> None:
        self.owner, self.rotate = owner, rotate

    def accept(self, goal: Any) -> bool:
        return valid_goal(goal, self.rotate)

    def execute(self, handle: Handle) -> None:
        self.owner.begin(handle, self.rotate)

    def cancel(self, handle: Handle) -> None:
        self.owner.cancel(handle)


class Nav2Primitives(Node):
    """Serves ``names.FORWARD`` and ``names.ROTATE`` through the robot's Nav2."""

    def __init__(
        self,
        navigation: NavigationState,
        spin: RemoteActionServer,
        backup: RemoteActionServer,
        drive: RemoteActionServer,
    ) -> None:
        super().__init__("nav2_primitives")
        self.navigation = navigation
        self.spin, self.backup, self.drive = spin, backup, drive
        self.motions: dict[int, _Motion] = {}
        self.routes: dict[str, int] = {}  # how many goals went each way

    def on_start(self) -> None:
        self.create_action_server(names.FORWARD, _Primitive(self, rotate=False))
        self.create_action_server(names.ROTATE, _Primitive(self, rotate=True))

    def _route(self, rotate: bool, amount: float) -> RemoteActionServer | None:
        remote = self.spin if rotate else (self.backup if amount < 0 else self.drive)
        return remote if remote.available else None

    def begin(self, handle: Handle, rotate: bool) -> None:
        amount = float(handle.goal.angle if rotate else handle.goal.distance)
        motion = _Motion(handle, amount)
        remote = self._route(rotate, amount)
        if remote is not None:
            motion.inner = self.runtime.bus.send_goal(remote.interface, handle.goal)
            route = remote.codec.ros_name
        else:  # no behaviour server: the pose the primitive would reach, as a Nav2 goal
            pose = self.navigation.pose
            if pose is None:
                handle.abort(PrimitiveResult(False, "no_odometry"))
                return
            motion.via_pose, route = True, names.NAVIGATE_TO_POSE
            motion.inner = self.runtime.bus.send_goal(
                names.MOVE_TO, MoveToGoal(pose=_reached(pose, rotate, amount))
            )
        self.routes[route] = self.routes.get(route, 0) + 1
        self.motions[handle.id] = motion
        motion.inner.on_feedback(lambda fb: self._feedback(motion, fb))
        motion.inner.on_done(lambda inner: self._done(motion, inner))

    def cancel(self, handle: Handle) -> None:
        motion = self.motions.get(handle.id)
        if motion is None or motion.inner is None or motion.inner.done:
            handle.canceled(PrimitiveResult(False, "canceled"))
        else:
            motion.inner.cancel()  # its end ends the primitive as canceled

    def _feedback(self, motion: _Motion, feedback: Any) -> None:
        if motion.via_pose:
            remaining = float(feedback.remaining_m)
        else:
            motion.done_so_far = abs(float(feedback))
            remaining = max(0.0, abs(motion.amount) - motion.done_so_far)
        motion.handle.publish_feedback(PrimitiveFeedback(remaining))

    def _done(self, motion: _Motion, inner: GoalHandle[Any, Any, Any]) -> None:
        self.motions.pop(motion.handle.id, None)
        handle, status = motion.handle, inner.status
        result = inner.result
        if isinstance(result, MoveToResult):
            result = PrimitiveResult(result.success, result.reason, result.travelled_m)
        elif result is None:
            result = PrimitiveResult(False, status.value)
        achieved = abs(motion.amount) if status is GoalStatus.SUCCEEDED else motion.done_so_far
        result = PrimitiveResult(
            result.success, result.reason, math.copysign(achieved, motion.amount)
        )
        if status is GoalStatus.SUCCEEDED:
            handle.succeed(result)
        elif status is GoalStatus.CANCELED or handle.cancel_requested:
            handle.canceled(PrimitiveResult(False, "canceled", result.achieved))
        else:
            handle.abort(result)


def _reached(pose: Pose2D, rotate: bool, amount: float) -> Pose2D:
    if rotate:
        return Pose2D(pose.x, pose.y, pose.theta + amount)
    c, s = math.cos(pose.theta), math.sin(pose.theta)
    return Pose2D(pose.x + amount * c, pose.y + amount * s, pose.theta)


def add_nav2_navigation(
    runtime: Runtime, ros: RosContext, cfg: SystemConfig, world: World, timeout_s: float
) -> list[RemoteActionServer]:
    """MoveTo for the edge's bus, served by the robot's ``/navigate_to_pose``, and the
    primitives by its behaviour server (or by ``/navigate_to_pose`` where it has none)."""
    pose = NavigationState(runtime.bus, pose_topic(cfg))
    places = {name: world.place(name) for name in world.home.places}
    codec = NavigateToPoseCodec(places, lambda: pose.pose)
    move_to = runtime.add(RemoteActionServer(ros, codec, timeout_s))
    spin, backup, drive = (
        runtime.add(RemoteActionServer(ros, behavior, timeout_s))
        for behavior in (SpinCodec(), BackUpCodec(), DriveOnHeadingCodec())
    )
    runtime.add(Nav2Primitives(pose, spin, backup, drive))
    return [move_to, spin, backup, drive]
