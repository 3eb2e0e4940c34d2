"""amiro's actions as ROS 2 action types: MoveTo, Forward, Search, RecognizeActivity and
behavior/run as ``amiro_interfaces`` actions, and MoveTo as Nav2's
``nav2_msgs/action/NavigateToPose``.

Optional fields of amiro's goals travel with a flag (``to_pose``, ``has_final_pose``), as
ROS 2 messages have no None.  The Nav2 mapping follows Nav2 Jazzy: a result's
``error_code`` is 0 on success, else the code of the Nav2 server that failed (planner
2xx, controller 1xx), read back into MoveTo's failure reasons.
"""

from __future__ import annotations

import json
import math
from typing import Any

from amiro.core import names
from amiro.core.bus import GoalStatus
from amiro.core.messages import Point, Pose2D
from amiro.deploy.behaviors import BehaviorFeedback, BehaviorGoal, BehaviorResult
from amiro.deploy.task_actions import (
    RecognizeActivityFeedback,
    RecognizeActivityGoal,
    RecognizeActivityResult,
    SearchFeedback,
    SearchGoal,
    SearchResult,
)
from amiro.navigation.move_to import MoveToFeedback, MoveToGoal, MoveToResult
from amiro.navigation.primitives import ForwardGoal, PrimitiveFeedback, PrimitiveResult
from amiro.ros2.interfaces import ActionCodec, WireError


def _pose2d(msg: Any, pose: Pose2D) -> Any:
    msg.x, msg.y, msg.theta = float(pose.x), float(pose.y), float(pose.theta)
    return msg


def _from_pose2d(msg: Any) -> Pose2D:
    return Pose2D(float(msg.x), float(msg.y), float(msg.theta))


class MoveToCodec(ActionCodec[MoveToGoal, MoveToFeedback, MoveToResult]):
    """``amiro_interfaces/action/MoveTo``: a place, a person or a pose."""

    def __init__(self, ros_name: str | None = None) -> None:
        super().__init__(names.MOVE_TO, "amiro_interfaces/action/MoveTo", ros_name)

    def goal_to_ros(self, goal: MoveToGoal) -> Any:
        msg = self.action.Goal(place=goal.place or "", approach=float(goal.approach))
        if goal.person is not None:
            msg.to_person = True
            msg.person.x, msg.person.y, msg.person.z = goal.person.x, goal.person.y, goal.person.z
        if goal.pose is not None:
            msg.to_pose = True
            _pose2d(msg.pose, goal.pose)
        return msg

    def goal_from_ros(self, msg: Any) -> MoveToGoal:
        return MoveToGoal(
            pose=_from_pose2d(msg.pose) if msg.to_pose else None,
            place=str(msg.place) or None,
            person=Point(msg.person.x, msg.person.y, msg.person.z) if msg.to_person else None,
            approach=float(msg.approach),
        )

    def feedback_to_ros(self, feedback: MoveToFeedback, elapsed_s: float) -> Any:
        msg = self.action.Feedback(
            remaining_m=float(feedback.remaining_m), recoveries=int(feedback.recoveries)
        )
        _pose2d(msg.pose, feedback.pose)
        return msg

    def feedback_from_ros(self, msg: Any) -> MoveToFeedback:
        return MoveToFeedback(_from_pose2d(msg.pose), float(msg.remaining_m), int(msg.recoveries))

    def result_to_ros(self, result: MoveToResult | None, status: GoalStatus) -> Any:
        if result is None:
            return self.action.Result(success=False, reason=status.value)
        msg = self.action.Result(
            success=result.success, reason=result.reason, travelled_m=float(result.travelled_m)
        )
        if result.final_pose is not None:
            msg.has_final_pose = True
            _pose2d(msg.final_pose, result.final_pose)
        return msg

    def result_from_ros(self, msg: Any, status: GoalStatus) -> MoveToResult:
        final = _from_pose2d(msg.final_pose) if msg.has_final_pose else None
        return MoveToResult(bool(msg.success), str(msg.reason), float(msg.travelled_m), final)

    def failure(self, reason: str) -> MoveToResult:
        return MoveToResult(False, reason)


class ForwardCodec(ActionCodec[ForwardGoal, PrimitiveFeedback, PrimitiveResult]):
    """``amiro_interfaces/action/Forward``: the forward primitive (speed 0: the server's)."""

    def __init__(self) -> None:
        super().__init__(names.FORWARD, "amiro_interfaces/action/Forward")

    def goal_to_ros(self, goal: ForwardGoal) -> Any:
        return self.action.Goal(distance=float(goal.distance), speed=float(goal.speed or 0.0))

    def goal_from_ros(self, msg: Any) -> ForwardGoal:
        speed = float(msg.speed)
        if not (math.isfinite(float(msg.distance)) and math.isfinite(speed) and speed >= 0.0):
            raise WireError("a Forward goal needs a finite distance and a speed >= 0")
        return ForwardGoal(float(msg.distance), speed or None)

    def feedback_to_ros(self, feedback: PrimitiveFeedback, elapsed_s: float) -> Any:
        return self.action.Feedback(remaining=float(feedback.remaining))

    def feedback_from_ros(self, msg: Any) -> PrimitiveFeedback:
        return PrimitiveFeedback(float(msg.remaining))

    def result_to_ros(self, result: PrimitiveResult | None, status: GoalStatus) -> Any:
        if result is None:
            return self.action.Result(success=False, reason=status.value)
        return self.action.Result(
            success=result.success, reason=result.reason, achieved=float(result.achieved)
        )

    def result_from_ros(self, msg: Any, status: GoalStatus) -> PrimitiveResult:
        return PrimitiveResult(bool(msg.success), str(msg.reason), float(msg.achieved))

    def failure(self, reason: str) -> PrimitiveResult:
        return PrimitiveResult(False, reason)


class SearchCodec(ActionCodec[SearchGoal, SearchFeedback, SearchResult]):
    """``amiro_interfaces/action/Search``: look for a named person."""

    def __init__(self) -> None:
        super().__init__(names.SEARCH, "amiro_interfaces/action/Search")

    def goal_to_ros(self, goal: SearchGoal) -> Any:
        return self.action.Goal(
            person=goal.person,
            dwell_s=float(goal.dwell_s),
            sightings=int(goal.sightings),
            side_steps=int(goal.side_steps),
        )

    def goal_from_ros(self, msg: Any) -> SearchGoal:
        if not str(msg.person):
            raise WireError("a Search goal needs a person")
        return SearchGoal(
            str(msg.person), float(msg.dwell_s), int(msg.sightings), int(msg.side_steps)
        )

    def feedback_to_ros(self, feedback: SearchFeedback, elapsed_s: float) -> Any:
        return self.action.Feedback(room=feedback.room, step=feedback.step)

    def feedback_from_ros(self, msg: Any) -> SearchFeedback:
        return SearchFeedback(str(msg.room), str(msg.step))

    def result_to_ros(self, result: SearchResult | None, status: GoalStatus) -> Any:
        if result is None:
            return self.action.Result(found=False, outcome=status.value)
        msg = self.action.Result(found=result.found, outcome=result.outcome, room=result.room)
        if result.position is not None:
            p = result.position
            msg.position.x, msg.position.y, msg.position.z = float(p.x), float(p.y), float(p.z)
        return msg

    def result_from_ros(self, msg: Any, status: GoalStatus) -> SearchResult:
        p = msg.position
        position = Point(float(p.x), float(p.y), float(p.z)) if msg.found else None
        return SearchResult(bool(msg.found), str(msg.outcome), position, str(msg.room))

    def failure(self, reason: str) -> SearchResult:
        return SearchResult(False, reason)


class RecognizeActivityCodec(
    ActionCodec[RecognizeActivityGoal, RecognizeActivityFeedback, RecognizeActivityResult]
):
    """``amiro_interfaces/action/RecognizeActivity``: watch a person for an activity."""

    def __init__(self) -> None:
        super().__init__(names.RECOGNIZE_ACTIVITY, "amiro_interfaces/action/RecognizeActivity")

    def goal_to_ros(self, goal: RecognizeActivityGoal) -> Any:
        return self.action.Goal(
            person=goal.person,
            activity=goal.activity,
            timeout_s=float(goal.timeout_s),
            confirmations=int(goal.confirmations),
            of_last=int(goal.of_last),
        )

    def goal_from_ros(self, msg: Any) -> RecognizeActivityGoal:
        if not str(msg.person):
            raise WireError("a RecognizeActivity goal needs a person")
        return RecognizeActivityGoal(
            str(msg.person),
            str(msg.activity),
            float(msg.timeout_s),
            int(msg.confirmations),
            int(msg.of_last),
        )

    def feedback_to_ros(self, feedback: RecognizeActivityFeedback, elapsed_s: float) -> Any:
        return self.action.Feedback(
            current=feedback.current, confirmations=int(feedback.confirmations)
        )

    def feedback_from_ros(self, msg: Any) -> RecognizeActivityFeedback:
        return RecognizeActivityFeedback(str(msg.current), int(msg.confirmations))

    def result_to_ros(self, result: RecognizeActivityResult | None, status: GoalStatus) -> Any:
        if result is None:
            return self.action.Result(recognised=False, outcome=status.value)
        return self.action.Result(recognised=result.recognised, outcome=result.outcome)

    def result_from_ros(self, msg: Any, status: GoalStatus) -> RecognizeActivityResult:
        return RecognizeActivityResult(bool(msg.recognised), str(msg.outcome))

    def failure(self, reason: str) -> RecognizeActivityResult:
        return RecognizeActivityResult(False, reason)


class BehaviorRunCodec(ActionCodec[BehaviorGoal, BehaviorFeedback, BehaviorResult]):
    """``amiro_interfaces/action/Run``: the payload (a blackboard) travels as a JSON object."""

    def __init__(self) -> None:
        super().__init__(names.BEHAVIOR_RUN, "amiro_interfaces/action/Run")

    def goal_to_ros(self, goal: BehaviorGoal) -> Any:
        return self.action.Goal(
            kind=goal.kind,
            payload_json=json.dumps(goal.payload, separators=(",", ":")),
            priority=-1 if goal.priority is None else goal.priority,
            single_task=goal.single_task,
        )

    def goal_from_ros(self, msg: Any) -> BehaviorGoal:
        try:
            payload = json.loads(str(msg.payload_json) or "{}")
        except json.JSONDecodeError as exc:
            raise WireError(f"payload_json is not JSON: {exc.msg}") from None
        if not isinstance(payload, dict):
            raise WireError("payload_json must hold a JSON object")
        priority = int(msg.priority)
        return BehaviorGoal(
            str(msg.kind), payload, None if priority < 0 else priority, bool(msg.single_task)
        )

    def feedback_to_ros(self, feedback: BehaviorFeedback, elapsed_s: float) -> Any:
        return self.action.Feedback(run=feedback.run, task=feedback.task)

    def feedback_from_ros(self, msg: Any) -> BehaviorFeedback:
        return BehaviorFeedback(str(msg.run), str(msg.task))

    def result_to_ros(self, result: BehaviorResult | None, status: GoalStatus) -> Any:
        if result is None:
            return self.action.Result(ok=False, outcome=status.value)
        return self.action.Result(ok=result.ok, outcome=result.outcome, run=result.run)

    def result_from_ros(self, msg: Any, status: GoalStatus) -> BehaviorResult:
        return BehaviorResult(bool(msg.ok), str(msg.outcome), str(msg.run))

    def failure(self, reason: str) -> BehaviorResult:
        return BehaviorResult(False, reason)


# Nav2 Jazzy's error codes (nav2_msgs/action/ComputePathToPose and FollowPath results, which
# bt_navigator passes on in NavigateToPose's result), and MoveTo's reasons for them.
NAV2_NONE = 0
NAV2_UNKNOWN = 9000  # NavigateToPose's own UNKNOWN in later Nav2 releases
NAV2_CODES = {
    "unreachable": 208,  # ComputePathToPose NO_VALID_PATH
    "no_pose": 202,  # ComputePathToPose TF_ERROR: no robot pose in the map frame
    "stuck": 105,  # FollowPath FAILED_TO_MAKE_PROGRESS
}
NOMINAL_SPEED = 0.3  # m/s, for Nav2's estimated_time_remaining


# Nav2 Jazzy's behaviour server (nav2_msgs Spin 70x, BackUp 71x, DriveOnHeading 72x): its
# codes that say more than "failed", as the primitives' reasons.
NAV2_BEHAVIOR_REASONS = {
    701: "timeout",
    702: "no_odometry",  # TF_ERROR: no robot pose
    703: "blocked",  # COLLISION_AHEAD
    711: "timeout",
    712: "no_odometry",
    713: "invalid_input",
    714: "blocked",
    721: "timeout",
    722: "no_odometry",
    723: "blocked",
    724: "invalid_input",
}


def nav2_reason(error_code: int, error_msg: str) -> str:
    """amiro's failure reason for a Nav2 result: the planner's codes (2xx) mean no path,
    the controller's (1xx) a robot that cannot follow it, the behaviour server's (7xx) a
    primitive that timed out, lost its pose or would collide; others keep Nav2's own code."""
    if 200 <= error_code < 300:
        return "no_pose" if error_code in (202,) else "unreachable"
    if 100 <= error_code < 200:
        return "no_pose" if error_code == 102 else "stuck"
    if error_code in NAV2_BEHAVIOR_REASONS:
        return NAV2_BEHAVIOR_REASONS[error_code]
    detail = f": {error_msg}" if error_msg else ""
    return f"nav2_error_{error_code}{detail}"


def nav2_outcome(msg: Any, status: GoalStatus, done: str) -> tuple[bool, str]:
    """A Nav2 action's result as (success, reason): ``done`` when it succeeded, ``canceled``,
    or the reason its error code maps to (:func:`nav2_reason`)."""
    if status is GoalStatus.SUCCEEDED:
        return True, done
    if status is GoalStatus.CANCELED:
        return False, "canceled"
    return False, nav2_reason(int(msg.error_code), str(msg.error_msg))


def duration(msg: Any, seconds: float) -> Any:
    whole = max(0.0, seconds)
    msg.sec = int(whole)
    msg.nanosec = int((whole - int(whole)) * 1e9)
    return msg


def yaw_to_quaternion(msg: Any, yaw: float) -> None:
    msg.x, msg.y = 0.0, 0.0
    msg.z, msg.w = math.sin(yaw / 2.0), math.cos(yaw / 2.0)


def _quaternion_yaw(q: Any) -> float:
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


class NavigateToPoseCodec(ActionCodec[MoveToGoal, MoveToFeedback, MoveToResult]):
    """MoveTo as Nav2's ``/navigate_to_pose``: a pose goal in the map frame.

    Serving, any Nav2 client drives amiro's MoveTo; calling, amiro's MoveTo drives a robot's
    own Nav2.  Places resolve to their pose here; a person goal needs the robot's pose
    (``robot_pose``) to stop ``approach`` metres short of her, facing her.
    """

    def __init__(
        self,
        places: dict[str, Pose2D] | None = None,
        robot_pose: Any = None,
        frame: str = "map",
    ) -> None:
        super().__init__(names.MOVE_TO, "nav2_msgs/action/NavigateToPose", "/navigate_to_pose")
        self.places = places or {}
        self.robot_pose = robot_pose  # () -> Pose2D | None
        self.frame = frame

    def target(self, goal: MoveToGoal) -> Pose2D:
        if goal.pose is not None:
            return goal.pose
        if goal.place is not None:
            if goal.place not in self.places:
                raise WireError(f"unknown place {goal.place!r}")
            return self.places[goal.place]
        if goal.person is None:
            raise WireError("a MoveTo goal needs a pose, a place or a person")
        here = (self.robot_pose() if self.robot_pose is not None else None) or Pose2D(0, 0, 0)
        person = goal.person
        yaw = math.atan2(person.y - here.y, person.x - here.x)
        back = min(goal.approach, math.hypot(person.x - here.x, person.y - here.y))
        return Pose2D(person.x - back * math.cos(yaw), person.y - back * math.sin(yaw), yaw)

    def goal_to_ros(self, goal: MoveToGoal) -> Any:
        pose = self.target(goal)
        msg = self.action.Goal()
        msg.pose.header.frame_id = self.frame
        msg.pose.pose.position.x, msg.pose.pose.position.y = float(pose.x), float(pose.y)
        yaw_to_quaternion(msg.pose.pose.orientation, pose.theta)
        return msg

    def goal_from_ros(self, msg: Any) -> MoveToGoal:
        frame = str(msg.pose.header.frame_id)
        if frame not in ("", self.frame):
            raise WireError(f"goal in frame {frame!r}: amiro navigates in {self.frame!r}")
        p = msg.pose.pose
        return MoveToGoal(
            pose=Pose2D(float(p.position.x), float(p.position.y), _quaternion_yaw(p.orientation))
        )

    def feedback_to_ros(self, feedback: MoveToFeedback, elapsed_s: float) -> Any:
        msg = self.action.Feedback(
            distance_remaining=float(feedback.remaining_m),
            number_of_recoveries=int(feedback.recoveries),
        )
        msg.current_pose.header.frame_id = self.frame
        pose = feedback.pose
        msg.current_pose.pose.position.x = float(pose.x)
        msg.current_pose.pose.position.y = float(pose.y)
        yaw_to_quaternion(msg.current_pose.pose.orientation, pose.theta)
        duration(msg.navigation_time, elapsed_s)
        duration(msg.estimated_time_remaining, feedback.remaining_m / NOMINAL_SPEED)
        return msg

    def feedback_from_ros(self, msg: Any) -> MoveToFeedback:
        p = msg.current_pose.pose
        pose = Pose2D(float(p.position.x), float(p.position.y), _quaternion_yaw(p.orientation))
        return MoveToFeedback(pose, float(msg.distance_remaining), int(msg.number_of_recoveries))

    def result_to_ros(self, result: MoveToResult | None, status: GoalStatus) -> Any:
        if status is GoalStatus.SUCCEEDED or status is GoalStatus.CANCELED:
            return self.action.Result(error_code=NAV2_NONE)
        reason = result.reason if result is not None else status.value
        return self.action.Result(error_code=NAV2_CODES.get(reason, NAV2_UNKNOWN), error_msg=reason)

    def result_from_ros(self, msg: Any, status: GoalStatus) -> MoveToResult:
        return MoveToResult(*nav2_outcome(msg, status, "arrived"))

    def failure(self, reason: str) -> MoveToResult:
        return MoveToResult(False, reason)
