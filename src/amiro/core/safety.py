"""The emergency stop's meaning, read in one place by everything that moves the base.

``names.EMERGENCY_STOP`` carries a std String, as on a ROS robot's stop button bridge:
"stop", "true", "on" or "1" (any case) engage it, anything else releases it.  The velocity
multiplexer and every robot adapter parse it with :func:`estop_engaged`, so a new spelling
is added here once and no reader can disagree with another.
"""

from __future__ import annotations

_ENGAGED = frozenset({"1", "true", "stop", "on"})


def estop_engaged(text: str) -> bool:
    """Whether an emergency-stop message engages the stop (else it releases it)."""
    return text.strip().lower() in _ENGAGED
