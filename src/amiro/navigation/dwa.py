"""The Dynamic Window Approach for an omnidirectional base (Fox, Burgard, Thrun 1997).

Each control cycle samples (vx, vy, wz) in the window the base can reach within
``window_s`` from its current velocity, rolls every sample forward at constant velocity over
the horizon, and discards those whose footprint comes closer than ``min_gap`` to anything in
the costmap (the map plus what the lidar sees).  Among the rest it picks the one closest to
the path-following reference while keeping a wide berth: the clearance term grows as the
rollout nears obstacles, so the robot swings wide around them as the paper's tuned DWA does
(Pepper's arms stay clear).  All samples are evaluated at once with numpy.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from amiro.core.messages import Pose2D, Twist
from amiro.navigation.costmap import Costmap

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class DwaParams:
    max_speed: float = 0.35
    max_turn: float = 1.0
    accel: float = 0.5  # m/s^2, as the base
    accel_turn: float = 2.0
    window_s: float = 0.3  # reachable-velocity window around the current velocity
    horizon_s: float = 1.2
    steps: int = 6
    samples: int = 7  # per linear axis
    turn_samples: int = 5
    min_gap: float = 0.05  # metres kept between the footprint and any obstacle
    berth: float = 0.35  # clearance beyond the footprint below which cost rises
    clearance_weight: float = 0.6
    turn_weight: float = 0.1
    goal_relief_m: float = (
        0.6  # this close to the goal, nearing obstacles down to its clearance is free
    )


class DynamicWindow:
    def __init__(self, costmap: Costmap, params: DwaParams | None = None) -> None:
        self.costmap = costmap
        self.params = p = params or DwaParams()
        axis = np.linspace(-1.0, 1.0, p.samples)
        turn = np.linspace(-1.0, 1.0, p.turn_samples)
        grid = np.stack(np.meshgrid(axis, axis, turn, indexing="ij"), axis=-1).reshape(-1, 3)
        dv, dw = p.accel * p.window_s, p.accel_turn * p.window_s
        self._offsets = grid * np.array([dv, dv, dw])  # the window around the current velocity
        t = np.linspace(p.horizon_s / p.steps, p.horizon_s, p.steps)
        self._times = t[None, :]

    def _candidates(self, current: tuple[float, float, float], preferred: Twist) -> FloatArray:
        p = self.params
        limits = np.array([p.max_speed, p.max_speed, p.max_turn])
        window = np.clip(np.asarray(current) + self._offsets, -limits, limits)
        pref = [preferred.linear.x, preferred.linear.y, preferred.angular.z]
        cand = np.vstack((window, [pref, [0.0, 0.0, pref[2]]]))
        speed = np.hypot(cand[:, 0], cand[:, 1])
        cand[:, :2] *= np.minimum(1.0, p.max_speed / np.maximum(speed, 1e-9))[:, None]
        return cand

    def rollout(self, pose: Pose2D, cand: FloatArray) -> tuple[FloatArray, FloatArray]:
        """Map-frame positions (n, steps) of each candidate held for the horizon."""
        t = self._times
        vx, vy, wz = cand[:, 0:1], cand[:, 1:2], cand[:, 2:3]
        th = pose.theta + wz * t
        # exact integration of a constant twist (arcs); straight when wz ~ 0
        small = np.abs(wz) < 1e-6
        wz_safe = np.where(small, 1.0, wz)
        s0, c0 = np.sin(pose.theta), np.cos(pose.theta)
        sin_int = np.where(small, s0 * t, (c0 - np.cos(th)) / wz_safe)
        cos_int = np.where(small, c0 * t, (np.sin(th) - s0) / wz_safe)
        xs = pose.x + vx * cos_int - vy * sin_int
        ys = pose.y + vx * sin_int + vy * cos_int
        return xs, ys

    def command(
        self,
        pose: Pose2D,
        current: tuple[float, float, float],
        preferred: Twist,
        goal: Pose2D | None = None,
    ) -> Twist:
        """The admissible velocity closest to ``preferred`` that keeps clear of obstacles.

        Near ``goal`` the berth term stops at the goal's own clearance: a goal 0.6 m from a
        wall must be reachable, and at creeping speed the berth cost would outweigh tracking.
        """
        p = self.params
        cm = self.costmap
        cand = self._candidates(current, preferred)
        xs, ys = self.rollout(pose, cand)
        clear = cm.clearance_many(xs, ys)
        here = cm.clearance_at(pose.x, pose.y)
        floor = cm.robot_radius + p.min_gap
        worst = clear.min(axis=1)
        # when already too close, moves that do not bring the robot closer stay allowed
        admissible = (worst >= floor) | (worst >= here - 1e-6)
        pref = np.array([preferred.linear.x, preferred.linear.y, preferred.angular.z])
        track = ((cand[:, 0] - pref[0]) ** 2 + (cand[:, 1] - pref[1]) ** 2) / p.max_speed**2
        track += p.turn_weight * ((cand[:, 2] - pref[2]) / p.max_turn) ** 2
        # only getting closer to obstacles costs: holding still or passing alongside is free
        margin = np.maximum(clear - cm.robot_radius, 0.0)
        near = np.exp(-margin / p.berth).mean(axis=1)
        ref_clear = here
        if goal is not None and goal.distance_to(pose) < p.goal_relief_m:
            ref_clear = min(here, cm.clearance_at(goal.x, goal.y))
        near_here = np.exp(-max(ref_clear - cm.robot_radius, 0.0) / p.berth)
        cost = track + p.clearance_weight * np.maximum(near - near_here, 0.0)
        cost[~admissible] = np.inf
        best = int(np.argmin(cost))
        if not np.isfinite(cost[best]):
            return Twist.planar(0.0, 0.0, preferred.angular.z)
        vx, vy, wz = cand[best]
        return Twist.planar(float(vx), float(vy), float(wz))
