"""The MoveTo action: plan, drive, watch the lidar for new obstacles, recover or fail cleanly.

Goal: a pose, a named place, or a person's position with an approach distance.  Feedback:
the remaining path length.  Result: success, or a reason ("unreachable", "stuck",
"canceled", "no_pose") so the behaviour engine can take the task's failure edge.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

from amiro.core import names
from amiro.core.bus import ActionServer, GoalHandle
from amiro.core.geometry import wrap_angle
from amiro.core.messages import (
    Header,
    LaserScan,
    Odometry,
    Path,
    Point,
    Pose2D,
    String,
    Twist,
)
from amiro.core.node import Node
from amiro.core.safety import estop_engaged
from amiro.navigation.costmap import Costmap
from amiro.navigation.dwa import DwaParams, DynamicWindow
from amiro.navigation.follower import FollowerLimits, PathFollower
from amiro.navigation.localization import Localizer, OracleLocalizer
from amiro.navigation.planner import GlobalPlanner

_BACKOFF_S = 1.5


@dataclass(frozen=True)
class MoveToGoal:
    pose: Pose2D | None = None
    place: str | None = None
    person: Point | None = None
    approach: float = 0.8


@dataclass(frozen=True)
class MoveToFeedback:
    pose: Pose2D
    remaining_m: float
    recoveries: int = 0  # recovery behaviours run so far for this goal (Nav2's count)


@dataclass(frozen=True)
class MoveToResult:
    success: bool
    reason: str
    travelled_m: float = 0.0
    final_pose: Pose2D | None = None


@dataclass
class _Active:
    handle: GoalHandle[MoveToGoal, MoveToFeedback, MoveToResult]
    follower: PathFollower
    travelled: float = 0.0
    last_pose: Pose2D | None = None
    progress_pose: Pose2D | None = None
    progress_time: float = 0.0
    recoveries: int = 0
    backoff_until: float = -1.0
    planned: bool = False


class MoveToNode(Node, ActionServer[MoveToGoal, MoveToFeedback, MoveToResult]):
    """Navigation front end: localisation in, A* global plan, DWA local control out."""

    def __init__(
        self,
        costmap: Costmap,
        places: dict[str, Pose2D],
        localizer: Localizer | None = None,
        limits: FollowerLimits | None = None,
        control_hz: float = 10.0,
        stuck_after_s: float = 6.0,
        max_recoveries: int = 2,
        dwa: DwaParams | None = None,
        pose_wait_s: float = 5.0,
    ) -> None:
        super().__init__("navigation")
        self.costmap = costmap
        self.planner = GlobalPlanner(costmap)
        self.places = places
        self.localizer: Localizer = localizer or OracleLocalizer()
        self.limits = limits or FollowerLimits()
        self.dwa = DynamicWindow(
            costmap,
            dwa or DwaParams(max_speed=self.limits.max_speed, max_turn=self.limits.max_turn),
        )
        self.velocity = (0.0, 0.0, 0.0)
        self.period = 1.0 / control_hz
        self.stuck_after_s = stuck_after_s
        self.max_recoveries = max_recoveries
        self.pose_wait_s = pose_wait_s  # a goal may come before localisation's first pose
        self.pose: Pose2D | None = None
        self.active: _Active | None = None
        self.emergency_stop = False

    def on_start(self) -> None:
        self.active = None
        self.cmd_pub = self.create_publisher(names.CMD_VEL_NAVIGATION, Twist)  # the mux's input
        self.path_pub = self.create_publisher(names.PATH, Path)
        self.localizer.attach(self, self._on_pose)
        self.create_subscription(names.ODOM, Odometry, self._on_odom, depth=1)
        self.create_subscription(names.SCAN, LaserScan, self._on_scan, depth=1)
        self.create_subscription(names.EMERGENCY_STOP, String, self._on_estop)
        self.create_action_server(names.MOVE_TO, self)
        self.create_timer(self.period, self._control)

    # --- inputs -------------------------------------------------------------------------
    def _on_pose(self, pose: Pose2D) -> None:
        self.pose = pose

    def _on_odom(self, msg: Odometry) -> None:
        self.velocity = (msg.twist.linear.x, msg.twist.linear.y, msg.twist.angular.z)

    def _on_scan(self, scan: LaserScan) -> None:
        if self.pose is None:
            return
        marked = self.costmap.mark_scan(scan, self.pose)
        if marked and self.active is not None and self._path_blocked(self.active.follower.path):
            self._replan(self.active)

    def _on_estop(self, msg: String) -> None:
        """The mux stops the base; here a goal only waits (held still is not "stuck")."""
        self.emergency_stop = estop_engaged(msg.data)

    # --- action server ------------------------------------------------------------------
    def accept(self, goal: MoveToGoal) -> bool:
        kinds = sum(x is not None for x in (goal.pose, goal.place, goal.person))
        return kinds == 1 and (goal.place is None or goal.place in self.places)

    def execute(self, handle: GoalHandle[MoveToGoal, MoveToFeedback, MoveToResult]) -> None:
        if self.active is not None:
            self.active.handle.abort(MoveToResult(False, "preempted_by_new_goal"))
        self.active = _Active(handle, PathFollower(self.limits), progress_time=self.now())
        if self.pose is not None:
            self._replan(self.active)
        # else the control loop plans at the first pose, or ends "no_pose" after pose_wait_s

    def canceled_result(
        self, handle: GoalHandle[MoveToGoal, MoveToFeedback, MoveToResult]
    ) -> MoveToResult:
        active = self.active
        travelled = active.travelled if active is not None and active.handle is handle else 0.0
        return MoveToResult(False, "canceled", travelled, self.pose)

    def cancel(self, handle: GoalHandle[MoveToGoal, MoveToFeedback, MoveToResult]) -> None:
        result = self.canceled_result(handle)  # before the goal's progress is dropped
        if self.active is not None and self.active.handle is handle:
            self.cmd_pub.publish(Twist())
            self.active = None
        handle.canceled(result)

    # --- planning and control -----------------------------------------------------------
    def _plan(self, goal: MoveToGoal, pose: Pose2D) -> list[Pose2D] | None:
        if goal.person is not None:
            return self.planner.plan_near(pose, goal.person, goal.approach)
        target = goal.pose if goal.pose is not None else self.places[goal.place or ""]
        return self.planner.plan_to_pose(pose, target)

    def _replan(self, active: _Active) -> None:
        assert self.pose is not None
        path = self._plan(active.handle.goal, self.pose)
        if path is None:
            self._finish(False, "unreachable")
            return
        active.follower.set_path(path)
        active.planned = True
        self.path_pub.publish(Path(Header(self.now(), "map"), tuple(path)))

    def _path_blocked(self, path: list[Pose2D]) -> bool:
        lethal = self.costmap.lethal
        frame = self.costmap.frame
        for a, b in itertools.pairwise(path):
            n = max(2, int(math.hypot(b.x - a.x, b.y - a.y) / frame.resolution) + 1)
            for i in range(n + 1):
                t = i / n
                r, c = frame.to_cell(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y))
                if frame.inside(r, c) and lethal[r, c]:
                    return True
        return False

    def _control(self) -> None:
        active = self.active
        if active is None:
            return
        if self.pose is None:
            if self.now() - active.progress_time > self.pose_wait_s:
                self._finish(False, "no_pose")
            return
        if not active.planned:
            self._replan(active)
            if self.active is not active:
                return
            active.progress_time = self.now()
        pose = self.pose
        if active.last_pose is not None:
            active.travelled += active.last_pose.distance_to(pose)
        active.last_pose = pose
        if self.emergency_stop:
            active.progress_time = self.now()  # held still on purpose: not "no progress"
            self.cmd_pub.publish(Twist())
            return
        if self.now() < active.backoff_until:
            self.cmd_pub.publish(self._backoff(pose))
            return
        twist, arrived = active.follower.command(pose)
        if arrived:
            self._finish(True, "arrived")
            return
        goal = active.follower.path[-1]
        self.cmd_pub.publish(self.dwa.command(pose, self.velocity, twist, goal))
        active.handle.publish_feedback(
            MoveToFeedback(pose, active.follower.remaining(pose), active.recoveries)
        )
        self._check_progress(active, pose)

    def _backoff(self, pose: Pose2D) -> Twist:
        """Move slowly away from the nearest obstacle (first recovery behaviour)."""
        gx, gy = self.costmap.away_from_obstacles(pose.x, pose.y)
        c, s = math.cos(pose.theta), math.sin(pose.theta)
        speed = 0.15
        return Twist.planar(speed * (c * gx + s * gy), speed * (-s * gx + c * gy), 0.0)

    def _check_progress(self, active: _Active, pose: Pose2D) -> None:
        """Recovery when the robot makes no progress: back off from the nearest obstacle,
        clear what the lidar marked, re-plan; give up after ``max_recoveries``."""
        ref = active.progress_pose
        moved = (
            ref is None
            or ref.distance_to(pose) > 0.1
            or abs(wrap_angle(ref.theta - pose.theta)) > 0.2
        )
        if moved:
            active.progress_pose = pose
            active.progress_time = self.now()
            return
        if self.now() - active.progress_time < self.stuck_after_s:
            return
        if active.recoveries >= self.max_recoveries:
            self._finish(False, "stuck")
            return
        active.recoveries += 1
        active.progress_time = self.now()
        active.backoff_until = self.now() + _BACKOFF_S
        self.log.info("no progress: recovery %d (back off, clear, re-plan)", active.recoveries)
        self.costmap.clear_observed()
        self._replan(active)

    def _finish(self, success: bool, reason: str) -> None:
        active = self.active
        if active is None:
            return
        self.active = None
        self.cmd_pub.publish(Twist())
        result = MoveToResult(success, reason, active.travelled, self.pose)
        if success:
            active.handle.succeed(result)
        else:
            active.handle.abort(result)
