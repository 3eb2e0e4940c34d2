"""Pepper 1.6's omnidirectional base: limited, accelerating, colliding, drifting.

The true pose is integrated from a commanded planar twist (robot frame) under velocity and
acceleration limits.  A step that would overlap an obstacle is refused and the robot stops,
as Pepper's bumpers do.  Odometry is integrated separately with the systematic drift the
AMIRO paper measured on Pepper (~10 deg per full turn, ~1 deg per metre) plus small noise.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from amiro.core.geometry import wrap_angle
from amiro.core.messages import Pose2D

FreeTest = Callable[[float, float, float], bool]  # (x, y, radius) -> no collision


@dataclass(frozen=True, slots=True)
class BaseLimits:
    max_linear: float = 0.35  # m/s, on the norm of (vx, vy)
    max_angular: float = 1.0  # rad/s
    max_linear_accel: float = 0.5  # m/s^2
    max_angular_accel: float = 2.0  # rad/s^2
    radius: float = 0.25  # m, footprint circle


@dataclass(frozen=True, slots=True)
class DriftParams:
    rotation_deg_per_rev: float = 10.0  # heading error per 360 deg turned
    heading_deg_per_m: float = 1.0  # heading error per metre travelled
    spread: float = 0.1  # relative run-to-run spread of the two systematic rates
    translation_scale_sigma: float = 0.01  # run-wide distance scale error (fraction)
    translation_noise: float = 0.005  # per-step noise, fraction of the step's length
    rotation_noise: float = 0.002  # per-step noise, fraction of the step's rotation


class Odometry:
    """Dead reckoning in the ``odom`` frame (starts at 0, 0, 0) with Pepper-like drift.

    The systematic rates are drawn once per run (random sign, magnitude around the paper's
    numbers) so a run is self-consistent; per-step noise rides on top.
    """

    def __init__(self, rng: np.random.Generator, params: DriftParams | None = None) -> None:
        self.params = p = params or DriftParams()
        self.rng = rng
        self.rot_rate = (
            float(rng.choice([-1.0, 1.0]))
            * p.rotation_deg_per_rev
            / 360.0
            * float(1.0 + p.spread * rng.standard_normal())
        )
        self.lin_rate = (
            float(rng.choice([-1.0, 1.0]))
            * math.radians(p.heading_deg_per_m)
            * float(1.0 + p.spread * rng.standard_normal())
        )
        self.scale = 1.0 + p.translation_scale_sigma * float(rng.standard_normal())
        self.pose = Pose2D()

    def reset(self, pose: Pose2D | None = None) -> None:
        self.pose = pose or Pose2D()

    def update(self, dx: float, dy: float, dtheta: float) -> Pose2D:
        """Add one true motion increment (robot frame at the step's start)."""
        p = self.params
        dist = math.hypot(dx, dy)
        n = self.rng.standard_normal(3)
        s = self.scale
        odx = dx * s + p.translation_noise * dist * float(n[0])
        ody = dy * s + p.translation_noise * dist * float(n[1])
        odth = (
            dtheta * (1.0 + self.rot_rate)
            + self.lin_rate * dist
            + p.rotation_noise * abs(dtheta) * float(n[2])
        )
        th = self.pose.theta + 0.5 * odth
        c, si = math.cos(th), math.sin(th)
        self.pose = Pose2D(
            self.pose.x + c * odx - si * ody,
            self.pose.y + si * odx + c * ody,
            wrap_angle(self.pose.theta + odth),
        )
        return self.pose


def _approach(current: float, target: float, max_delta: float) -> float:
    return current + max(-max_delta, min(max_delta, target - current))


class OmniBase:
    """True kinematics of the base; ``step`` integrates and checks collisions."""

    CONTACT_MARGIN = 0.02  # m: the robot counts as still touching within this distance

    def __init__(
        self,
        pose: Pose2D,
        limits: BaseLimits | None = None,
        odometry: Odometry | None = None,
    ) -> None:
        self.limits = limits or BaseLimits()
        self.pose = pose
        self.velocity = (0.0, 0.0, 0.0)  # vx, vy (robot frame), wz: actual
        self.command = (0.0, 0.0, 0.0)  # clamped target
        self.odometry = odometry
        self.collisions = 0
        self.in_contact = False
        self.travelled = 0.0
        self.turned = 0.0

    def set_command(self, vx: float, vy: float, wz: float) -> None:
        """Target twist in the robot frame, clamped to the speed limits."""
        lim = self.limits
        norm = math.hypot(vx, vy)
        if norm > lim.max_linear:
            vx, vy = vx * lim.max_linear / norm, vy * lim.max_linear / norm
        wz = max(-lim.max_angular, min(lim.max_angular, wz))
        if not all(math.isfinite(v) for v in (vx, vy, wz)):
            vx = vy = wz = 0.0
        self.command = (vx, vy, wz)

    def stop(self) -> None:
        """Zero command and velocity at once (emergency stop)."""
        self.command = (0.0, 0.0, 0.0)
        self.velocity = (0.0, 0.0, 0.0)

    def step(self, dt: float, is_free: FreeTest | None = None) -> bool:
        """Advance ``dt`` seconds; returns True if this step began a new collision."""
        lim = self.limits
        vx0, vy0, wz0 = self.velocity
        tx, ty, tw = self.command
        # linear acceleration limited on the vector, so diagonal moves stay straight
        ddx, ddy = tx - vx0, ty - vy0
        dnorm = math.hypot(ddx, ddy)
        max_dv = lim.max_linear_accel * dt
        if dnorm > max_dv:
            ddx, ddy = ddx * max_dv / dnorm, ddy * max_dv / dnorm
        vx, vy = vx0 + ddx, vy0 + ddy
        wz = _approach(wz0, tw, lim.max_angular_accel * dt)
        # integrate with the mid-step heading (exact for straight lines and pure turns)
        dth = wz * dt
        dx_r, dy_r = vx * dt, vy * dt
        th = self.pose.theta + 0.5 * dth
        c, s = math.cos(th), math.sin(th)
        nx = self.pose.x + c * dx_r - s * dy_r
        ny = self.pose.y + s * dx_r + c * dy_r
        new_contact = False
        if is_free is not None and not is_free(nx, ny, lim.radius):
            self.velocity = (0.0, 0.0, 0.0)
            if not self.in_contact:
                self.collisions += 1
                new_contact = True
            self.in_contact = True
            return new_contact
        self.pose = Pose2D(nx, ny, wrap_angle(self.pose.theta + dth))
        self.velocity = (vx, vy, wz)
        self.travelled += math.hypot(dx_r, dy_r)
        self.turned += abs(dth)
        if self.odometry is not None:
            # increments in the frame of the step's start heading, as wheel odometry sees them
            hc, hs = math.cos(0.5 * dth), math.sin(0.5 * dth)
            self.odometry.update(hc * dx_r - hs * dy_r, hs * dx_r + hc * dy_r, dth)
        if self.in_contact and (
            is_free is None or is_free(nx, ny, lim.radius + self.CONTACT_MARGIN)
        ):
            self.in_contact = False
        return False
