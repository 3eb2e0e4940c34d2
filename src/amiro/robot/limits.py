"""Commands clamped to what the robot can do: speeds, accelerations, base type, head range.

Every velocity command leaving amiro for a real base goes through a :class:`VelocityLimiter`:
a planar twist (the z-linear and x/y-angular parts are dropped), no lateral velocity on a
differential base, speeds within the profile's limits and changes within its accelerations.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from amiro.core import names
from amiro.core.messages import Twist
from amiro.robot.profile import BaseType, Head, Limits


@dataclass(frozen=True, slots=True)
class Planar:
    vx: float = 0.0
    vy: float = 0.0
    wz: float = 0.0

    def to_twist(self) -> Twist:
        return Twist.planar(self.vx, self.vy, self.wz)


def _clip(value: float, limit: float) -> float:
    return max(-limit, min(limit, value))


def _finite(value: float) -> float:
    return value if math.isfinite(value) else 0.0


class VelocityLimiter:
    """Turns the latest wanted twist into the command to send now, step by step."""

    def __init__(self, base: BaseType, limits: Limits) -> None:
        self.base = base
        self.limits = limits
        self.current = Planar()
        self.clamped = 0  # wanted twists that exceeded a speed limit or the base type

    def target(self, twist: Twist) -> Planar:
        """The wanted twist within the speed limits and the base's degrees of freedom."""
        lim = self.limits
        vx, vy = _finite(twist.linear.x), _finite(twist.linear.y)
        wz = _finite(twist.angular.z)
        if self.base == "differential":
            vy = 0.0
        norm = math.hypot(vx, vy)
        if norm > lim.max_linear:
            vx, vy = vx * lim.max_linear / norm, vy * lim.max_linear / norm
        out = Planar(vx, vy, _clip(wz, lim.max_angular))
        if out != Planar(twist.linear.x, twist.linear.y, twist.angular.z):
            self.clamped += 1
        return out

    def step(self, target: Planar, dt: float) -> Planar:
        """Move the command toward ``target`` within the accelerations over ``dt`` seconds."""
        lim = self.limits
        dvx, dvy = target.vx - self.current.vx, target.vy - self.current.vy
        dv = math.hypot(dvx, dvy)
        max_dv = lim.max_linear_accel * dt
        if dv > max_dv:
            dvx, dvy = dvx * max_dv / dv, dvy * max_dv / dv
        dwz = _clip(target.wz - self.current.wz, lim.max_angular_accel * dt)
        self.current = Planar(self.current.vx + dvx, self.current.vy + dvy, self.current.wz + dwz)
        return self.current

    def reset(self) -> None:
        self.current = Planar()


def clamp_head(head: Head, targets: dict[str, float]) -> dict[str, float]:
    """amiro's ``HeadYaw``/``HeadPitch`` targets within the joint ranges (others dropped)."""
    ranges = {names.HEAD_YAW: head.yaw_limits, names.HEAD_PITCH: head.pitch_limits}
    return {
        joint: min(ranges[joint][1], max(ranges[joint][0], angle))
        for joint, angle in targets.items()
        if joint in ranges and math.isfinite(angle)
    }
