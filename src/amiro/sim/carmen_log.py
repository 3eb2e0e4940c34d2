"""Simulated CARMEN logs: drive Pepper's base along a route in a map, log lidar and odometry.

The robot follows the route at constant speed, turning in place at the corners; odometry
drifts as Pepper's does (``DriftParams``), the 180-degree front lidar has the sim's range
noise.  The true pose goes into each FLASER's reference triple, for scoring only.
"""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import numpy as np

from amiro.core.geometry import wrap_angle
from amiro.core.gridmap import GridMap
from amiro.core.messages import Pose2D
from amiro.navigation.carmen import flaser_line, odom_line
from amiro.sim.base import DriftParams, Odometry
from amiro.sim.lidar import Lidar, LidarParams

MAX_RANGE_M = 12.0


def drive(
    route: list[tuple[float, float]], speed: float, turn_rate: float, dt: float
) -> list[Pose2D]:
    """Poses every ``dt`` seconds along the route (straight legs, turns in place)."""
    poses: list[Pose2D] = []
    heading = math.atan2(route[1][1] - route[0][1], route[1][0] - route[0][0])
    for (x0, y0), (x1, y1) in itertools.pairwise(route):
        target = math.atan2(y1 - y0, x1 - x0)
        while abs(wrap_angle(target - heading)) > 1e-9:
            heading = wrap_angle(
                heading + max(-turn_rate * dt, min(turn_rate * dt, wrap_angle(target - heading)))
            )
            poses.append(Pose2D(x0, y0, heading))
        length = math.hypot(x1 - x0, y1 - y0)
        steps = max(1, round(length / (speed * dt)))
        for k in range(1, steps + 1):
            t = k / steps
            poses.append(Pose2D(x0 + t * (x1 - x0), y0 + t * (y1 - y0), heading))
    return poses


def write_log(
    path: Path,
    grid: GridMap,
    route: list[tuple[float, float]],
    rng: np.random.Generator,
    speed: float = 0.35,
    turn_rate: float = 0.8,
    scan_hz: float = 2.0,
    drift: DriftParams | None = None,
) -> int:
    """Write a CARMEN log of the drive; returns the number of scans."""
    rng_odom, rng_lidar = rng.spawn(2)
    odometry = Odometry(rng_odom, drift or DriftParams())
    lidar = Lidar(LidarParams(beams=360, range_max=MAX_RANGE_M))
    front = np.abs(lidar.angles) <= math.pi / 2 + 1e-9
    dt = 1.0 / scan_hz
    poses = drive(route, speed, turn_rate, dt)
    lines = []
    prev = poses[0]
    for i, pose in enumerate(poses):
        stamp = i * dt
        if i:
            c, s = math.cos(prev.theta), math.sin(prev.theta)
            dx, dy = pose.x - prev.x, pose.y - prev.y
            odometry.update(c * dx + s * dy, -s * dx + c * dy, wrap_angle(pose.theta - prev.theta))
        prev = pose
        ranges = lidar.scan(grid, pose, stamp, rng_lidar).ranges[front]
        ranges = np.where(np.isfinite(ranges), ranges, MAX_RANGE_M)  # CARMEN: max = no return
        odom = odometry.pose
        lines.append(odom_line(stamp, odom, speed, 0.0))
        lines.append(flaser_line(stamp, ranges, pose, odom))
    path.write_text("# amiro simulated CARMEN log\n" + "\n".join(lines) + "\n", encoding="utf-8")
    return len(poses)
