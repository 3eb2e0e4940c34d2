"""The one writer of ``/cmd_vel``: a velocity multiplexer with an emergency-stop lock.

Modelled on ROS's ``twist_mux``: every source of base motion publishes on its own input
topic, each input has a priority and a timeout, and the mux forwards a message only from
the most urgent input that published within its timeout; a source that goes quiet loses
the base after its timeout, to the next live input's last twist, or to one zero twist when
none is left.
Where twist_mux has lock topics that mute inputs below their priority, amiro has one lock
above every input, the emergency stop (``names.EMERGENCY_STOP``, read by
:func:`amiro.core.safety.estop_engaged`): while it is engaged the mux sends zero at once,
then again every check period, and drops every input; after release a source must publish
again to move the base.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import partial

from amiro.core import names
from amiro.core.messages import String, Twist
from amiro.core.node import Node
from amiro.core.safety import estop_engaged


@dataclass(frozen=True)
class MuxInput:
    """One source of base motion: its topic, priority (higher wins) and timeout."""

    name: str
    topic: str
    priority: int
    timeout_s: float = 0.5


DEFAULT_INPUTS = (
    MuxInput("teleop", names.CMD_VEL_TELEOP, 100),
    MuxInput("navigation", names.CMD_VEL_NAVIGATION, 50),
    MuxInput("primitives", names.CMD_VEL_PRIMITIVES, 10),
)


class VelocityMuxNode(Node):
    """Forwards the most urgent live input to ``names.CMD_VEL``; the emergency stop wins."""

    def __init__(
        self, inputs: tuple[MuxInput, ...] = DEFAULT_INPUTS, check_period_s: float = 0.05
    ) -> None:
        super().__init__("velocity_mux")
        if len({i.priority for i in inputs}) != len(inputs):
            raise ValueError("velocity mux inputs need distinct priorities")
        self.inputs = tuple(sorted(inputs, key=lambda i: -i.priority))
        self.check_period_s = check_period_s
        self.locked = False
        self.selected: MuxInput | None = None  # whose twist the base last got
        self._last: dict[str, tuple[float, Twist]] = {}  # input -> when, what it last sent

    def on_start(self) -> None:
        self.locked = False
        self.selected = None
        self._last = {}
        self.pub = self.create_publisher(names.CMD_VEL, Twist)
        for source in self.inputs:
            self.create_subscription(source.topic, Twist, partial(self._on_input, source), depth=1)
        self.create_subscription(names.EMERGENCY_STOP, String, self._on_estop)
        self.create_timer(self.check_period_s, self._check_timeouts)

    def active(self) -> MuxInput | None:
        """The most urgent input that published within its timeout (None while locked)."""
        if self.locked:
            return None
        now = self.now()
        for source in self.inputs:
            if now - self._last.get(source.name, (-math.inf, None))[0] <= source.timeout_s:
                return source
        return None

    def _on_input(self, source: MuxInput, msg: Twist) -> None:
        if self.locked:
            return
        self._last[source.name] = (self.now(), msg)
        if self.active() is source:
            self._forward(source, msg)

    def _forward(self, source: MuxInput | None, msg: Twist) -> None:
        self.selected = source
        self.pub.publish(msg)

    def _on_estop(self, msg: String) -> None:
        engaged = estop_engaged(msg.data)
        if engaged and not self.locked:
            self.log.warning("emergency stop engaged: base stopped, inputs dropped")
        self.locked = engaged
        if engaged:
            self._last.clear()
            self.selected = None
            self.pub.publish(Twist())

    def _check_timeouts(self) -> None:
        if self.locked:  # held at zero: a driver that missed the first zero still stops
            self.pub.publish(Twist())
            return
        if self.selected is None or self.active() is self.selected:
            return
        # the selected source went quiet: it loses the base, to the next live input or to a stop
        after = self.active()
        self._forward(after, Twist() if after is None else self._last[after.name][1])
