"""Path following for an omnidirectional base: pure pursuit on the path's projection.

The carrot is the point ``lookahead`` metres further along the path than the robot's
projection onto it, so corners are cut by far less than the look-ahead.  Pepper's base moves
sideways as easily as forwards, but people read a robot that faces where it goes as safer,
so the body turns towards the travel direction while it translates; near the goal it slows
down and turns to the goal heading.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

from amiro.core.geometry import wrap_angle
from amiro.core.messages import Pose2D, Twist


@dataclass(frozen=True)
class FollowerLimits:
    max_speed: float = 0.35
    max_turn: float = 1.0
    lookahead: float = 0.35
    goal_tolerance: float = 0.04
    heading_tolerance: float = 0.08
    slow_radius: float = 0.6  # within this the body turns to the goal heading
    decel: float = 0.4  # m/s^2 planned braking (below the base's 0.5): stop on the goal


def _clamp(v: float, limit: float) -> float:
    return max(-limit, min(limit, v))


class PathFollower:
    def __init__(self, limits: FollowerLimits | None = None) -> None:
        self.limits = limits or FollowerLimits()
        self.path: list[Pose2D] = []
        self._segment = 0

    def set_path(self, path: list[Pose2D]) -> None:
        self.path = path
        self._segment = 0

    def _project(self, pose: Pose2D) -> tuple[int, float]:
        """Closest segment (from the current one on, never going back) and position on it."""
        best = (self._segment, 0.0, math.inf)
        for i in range(self._segment, len(self.path) - 1):
            a, b = self.path[i], self.path[i + 1]
            dx, dy = b.x - a.x, b.y - a.y
            length2 = dx * dx + dy * dy
            t = 0.0 if length2 == 0 else ((pose.x - a.x) * dx + (pose.y - a.y) * dy) / length2
            t = min(1.0, max(0.0, t))
            d = math.hypot(a.x + t * dx - pose.x, a.y + t * dy - pose.y)
            if d < best[2] - 1e-9:
                best = (i, t, d)
        return best[0], best[1]

    def _carrot(self, segment: int, t: float) -> tuple[float, float]:
        """The point ``lookahead`` metres along the path from (segment, t)."""
        left = self.limits.lookahead
        a, b = self.path[segment], self.path[segment + 1]
        x, y = a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)
        for i in range(segment, len(self.path) - 1):
            b = self.path[i + 1]
            step = math.hypot(b.x - x, b.y - y)
            if step >= left:
                f = left / step
                return x + f * (b.x - x), y + f * (b.y - y)
            left -= step
            x, y = b.x, b.y
        return x, y

    def remaining(self, pose: Pose2D) -> float:
        if not self.path:
            return 0.0
        pts = [pose, *self.path[self._segment + 1 :]]
        return sum(math.hypot(b.x - a.x, b.y - a.y) for a, b in itertools.pairwise(pts))

    def command(self, pose: Pose2D) -> tuple[Twist, bool]:
        """Velocity for this control cycle and whether the goal pose is reached."""
        lim = self.limits
        if not self.path:
            return Twist(), True
        goal = self.path[-1]
        dist_goal = pose.distance_to(goal)
        if dist_goal <= lim.goal_tolerance or len(self.path) == 1:
            err = wrap_angle(goal.theta - pose.theta)
            if abs(err) <= lim.heading_tolerance and dist_goal <= lim.goal_tolerance:
                return Twist(), True
            vx_map = vy_map = 0.0
            if dist_goal > lim.goal_tolerance:  # single-pose path: creep onto it
                vx_map = (goal.x - pose.x) / dist_goal * min(lim.max_speed, dist_goal)
                vy_map = (goal.y - pose.y) / dist_goal * min(lim.max_speed, dist_goal)
            vx, vy = _to_robot(pose, vx_map, vy_map)
            return Twist.planar(vx, vy, _clamp(2.0 * err, lim.max_turn)), False
        self._segment, t = self._project(pose)
        cx, cy = self._carrot(self._segment, t)
        dx, dy = cx - pose.x, cy - pose.y
        dist = math.hypot(dx, dy) or 1e-9
        speed = max(0.05, min(lim.max_speed, math.sqrt(2.0 * lim.decel * dist_goal)))
        heading = math.atan2(dy, dx)
        facing_error = wrap_angle(heading - pose.theta)
        if abs(facing_error) > 0.6:  # turn first, then go: smooth and predictable
            speed *= 0.3
        vx, vy = _to_robot(pose, speed * dx / dist, speed * dy / dist)
        target_heading = heading if dist_goal > lim.slow_radius else goal.theta
        wz = _clamp(2.0 * wrap_angle(target_heading - pose.theta), lim.max_turn)
        return Twist.planar(vx, vy, wz), False


def _to_robot(pose: Pose2D, vx_map: float, vy_map: float) -> tuple[float, float]:
    c, s = math.cos(pose.theta), math.sin(pose.theta)
    return c * vx_map + s * vy_map, -s * vx_map + c * vy_map
