"""The bus topics of the robot port: what every robot adapter reads and writes.

The simulator, a ROS 2 robot and Pepper over NAOqi all offer these names with these types,
so the rest of amiro never knows which robot it drives.
"""

from __future__ import annotations

from amiro.core import names

# robot -> amiro

# amiro -> robot

HEAD_YAW, HEAD_PITCH = names.HEAD_YAW, names.HEAD_PITCH


def estop_engaged(msg: str) -> bool:
    """The emergency-stop topic's meaning, as navigation reads it."""
    return msg.lower() in ("1", "true", "stop", "on")
