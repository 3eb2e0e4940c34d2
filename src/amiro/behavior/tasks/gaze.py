"""Where the robot looks: head commands shared by the tasks that watch people."""

from __future__ import annotations

import math

from amiro.behavior.task import TaskContext
from amiro.core import names
from amiro.core.messages import Header, JointState, Point

CAMERA_HEIGHT_M = 1.15  # Pepper's head camera above the floor


def point_head(ctx: TaskContext, yaw: float, pitch: float = 0.0) -> None:
    """Head joint targets in radians (Pepper's convention: positive pitch looks down)."""
    ctx.bus.publish(
        names.HEAD_CMD,
        JointState(Header(ctx.now(), ""), (names.HEAD_YAW, names.HEAD_PITCH), (yaw, pitch)),
    )


def look_at(ctx: TaskContext, target: Point, camera_height: float = CAMERA_HEIGHT_M) -> bool:
    """Turn the head towards a point of the map; False when the robot's pose is unknown."""
    pose = ctx.need(ctx.modules.navigation, "navigation").pose
    if pose is None:
        return False
    dx, dy = target.x - pose.x, target.y - pose.y
    yaw = math.atan2(dy, dx) - pose.theta
    yaw = (yaw + math.pi) % (2 * math.pi) - math.pi
    pitch = math.atan2(camera_height - target.z, math.hypot(dx, dy))
    point_head(ctx, yaw, pitch)
    return True
