"""amiro's primitives as Nav2's behaviour server actions: ``/spin`` (``nav2_msgs/action/Spin``),
``/backup`` (``BackUp``) and ``/drive_on_heading`` (``DriveOnHeading``), Nav2 Jazzy's types.

A goal's feedback on the bus is the distance travelled so far (Nav2's own feedback), the
result a :class:`PrimitiveResult` whose reason comes from Nav2's error code
(:func:`amiro.deploy.codecs.nav2_reason`); :class:`amiro.deploy.nav2.Nav2Primitives` turns
both into the primitive's own feedback and result.
"""

from __future__ import annotations

import math
from typing import Any

from amiro.core import names
from amiro.core.bus import GoalStatus
from amiro.deploy.codecs import duration, nav2_outcome
from amiro.navigation.primitives import ForwardGoal, PrimitiveResult, RotateGoal
from amiro.ros2.interfaces import ActionCodec, WireError

DEFAULT_SPEED = 0.15  # m/s: a goal that names none (Nav2 requires a speed)
NAV2_NONE = 0


def time_allowance(amount: float, rate: float) -> float:
    """Seconds Nav2 may take before TIMEOUT: three times the nominal duration, at least 10."""
    return max(10.0, 3.0 * abs(amount) / max(rate, 1e-3))


class _Nav2Behavior(ActionCodec[Any, float, PrimitiveResult]):
    def result_to_ros(self, result: PrimitiveResult | None, status: GoalStatus) -> Any:
        if status is GoalStatus.SUCCEEDED:
            return self.action.Result(error_code=NAV2_NONE)
        reason = result.reason if result is not None else status.value
        return self.action.Result(error_code=self.unknown, error_msg=reason)

    def result_from_ros(self, msg: Any, status: GoalStatus) -> PrimitiveResult:
        return PrimitiveResult(*nav2_outcome(msg, status, "done"))

    def failure(self, reason: str) -> PrimitiveResult:
        return PrimitiveResult(False, reason)

    unknown = 0  # the action's UNKNOWN error code


class SpinCodec(_Nav2Behavior):
    """ROTATE as ``nav2_msgs/action/Spin``: ``target_yaw`` is the relative angle."""

    unknown = 700

    def __init__(self, turn_rate: float = 0.6) -> None:
        super().__init__(names.NAV2_SPIN, "nav2_msgs/action/Spin")
        self.turn_rate = turn_rate

    def goal_to_ros(self, goal: RotateGoal) -> Any:
        msg = self.action.Goal(target_yaw=float(goal.angle))
        duration(msg.time_allowance, time_allowance(goal.angle, self.turn_rate))
        return msg

    def goal_from_ros(self, msg: Any) -> RotateGoal:
        return RotateGoal(float(msg.target_yaw))

    def feedback_to_ros(self, feedback: float, elapsed_s: float) -> Any:
        return self.action.Feedback(angular_distance_traveled=float(feedback))

    def feedback_from_ros(self, msg: Any) -> float:
        return float(msg.angular_distance_traveled)


class _Straight(_Nav2Behavior):
    """BackUp and DriveOnHeading: ``target.x`` the distance, ``speed`` signed as Nav2 wants."""

    backwards = False

    def goal_to_ros(self, goal: ForwardGoal) -> Any:
        sign = -1.0 if self.backwards else 1.0
        speed = float(goal.speed or DEFAULT_SPEED)
        msg = self.action.Goal(speed=sign * speed)
        msg.target.x = sign * abs(float(goal.distance))
        duration(msg.time_allowance, time_allowance(goal.distance, speed))
        return msg

    def goal_from_ros(self, msg: Any) -> ForwardGoal:
        if msg.target.y != 0.0 or msg.target.z != 0.0 or not math.isfinite(msg.target.x):
            raise WireError("only target.x may be set")
        sign = -1.0 if self.backwards else 1.0
        return ForwardGoal(sign * abs(float(msg.target.x)), abs(float(msg.speed)) or None)

    def feedback_to_ros(self, feedback: float, elapsed_s: float) -> Any:
        return self.action.Feedback(distance_traveled=float(feedback))

    def feedback_from_ros(self, msg: Any) -> float:
        return float(msg.distance_traveled)


class BackUpCodec(_Straight):
    """FORWARD with a negative distance as ``nav2_msgs/action/BackUp``."""

    unknown = 710
    backwards = True

    def __init__(self) -> None:
        super().__init__(names.NAV2_BACKUP, "nav2_msgs/action/BackUp")


class DriveOnHeadingCodec(_Straight):
    """FORWARD with a positive distance as ``nav2_msgs/action/DriveOnHeading``."""

    unknown = 720

    def __init__(self) -> None:
        super().__init__(names.NAV2_DRIVE_ON_HEADING, "nav2_msgs/action/DriveOnHeading")
