"""The velocity multiplexer alone on a bus: priority, timeout, the emergency-stop lock."""

from __future__ import annotations

import pytest

from amiro.core import names
from amiro.core.clock import SimClock
from amiro.core.messages import String, Twist
from amiro.core.runtime import Runtime
from amiro.core.safety import estop_engaged
from amiro.robot.velocity_mux import DEFAULT_INPUTS, MuxInput, VelocityMuxNode

TELEOP = Twist.planar(0.1, 0.0, 0.0)
NAV = Twist.planar(0.3, 0.0, 0.2)
PRIM = Twist.planar(-0.15, 0.0, 0.0)
STILL = Twist()


class Rig:
    def __init__(self) -> None:
        self.rt = Runtime(SimClock())
        self.mux = self.rt.add(VelocityMuxNode())
        self.out: list[tuple[float, Twist]] = []
        self.rt.bus.subscribe(
            names.CMD_VEL, Twist, lambda m: self.out.append((self.rt.clock.now(), m)), depth=1000
        )
        self.rt.start()

    def send(self, topic: str, twist: Twist) -> None:
        self.rt.bus.publish(topic, twist)
        self.rt.spin_for(0.0)

    def estop(self, text: str) -> None:
        self.rt.bus.publish(names.EMERGENCY_STOP, String(text))
        self.rt.spin_for(0.0)

    def last(self) -> Twist:
        return self.out[-1][1]


def test_the_more_urgent_input_wins_and_the_other_is_dropped() -> None:
    rig = Rig()
    rig.send(names.CMD_VEL_PRIMITIVES, PRIM)
    assert rig.last() == PRIM  # alone: forwarded at once
    rig.send(names.CMD_VEL_NAVIGATION, NAV)
    assert rig.last() == NAV
    n = len(rig.out)
    rig.send(names.CMD_VEL_PRIMITIVES, PRIM)  # navigation is live: primitives muted
    assert len(rig.out) == n
    rig.send(names.CMD_VEL_TELEOP, TELEOP)
    rig.send(names.CMD_VEL_NAVIGATION, NAV)
    assert rig.last() == TELEOP and rig.mux.selected is not None
    assert rig.mux.selected.name == "teleop"


def test_a_quiet_source_loses_the_base_after_its_timeout() -> None:
    rig = Rig()
    timeout = next(i.timeout_s for i in DEFAULT_INPUTS if i.topic == names.CMD_VEL_NAVIGATION)
    rig.send(names.CMD_VEL_NAVIGATION, NAV)
    rig.rt.spin_for(timeout * 0.8)
    rig.send(names.CMD_VEL_PRIMITIVES, PRIM)
    assert rig.last() == NAV  # still within navigation's timeout
    rig.rt.spin_for(timeout * 0.5)  # navigation has gone quiet past its timeout
    assert rig.last() == PRIM  # the live lower source takes over at once
    rig.rt.spin_for(timeout)  # and goes quiet too
    assert rig.last() == STILL and rig.mux.active() is None  # nobody left: one zero
    n = len(rig.out)
    rig.rt.spin_for(1.0)
    assert len(rig.out) == n
    rig.send(names.CMD_VEL_NAVIGATION, NAV)
    assert rig.last() == NAV


def test_a_quiet_source_with_a_live_lower_one_hands_over_without_a_stop() -> None:
    rig = Rig()
    rig.send(names.CMD_VEL_NAVIGATION, NAV)
    for _ in range(12):  # primitives keep publishing at 10 Hz, navigation stops
        rig.rt.spin_for(0.1)
        rig.send(names.CMD_VEL_PRIMITIVES, PRIM)
    assert rig.last() == PRIM
    assert STILL not in [t for _, t in rig.out]


def test_the_emergency_stop_zeroes_at_once_drops_inputs_and_releases() -> None:
    rig = Rig()
    rig.send(names.CMD_VEL_TELEOP, TELEOP)
    rig.estop("STOP")
    stopped_at, first = rig.rt.clock.now(), len(rig.out) - 1
    assert rig.last() == STILL and rig.out[-1][0] == stopped_at  # no tick later
    rig.send(names.CMD_VEL_TELEOP, TELEOP)  # not even the most urgent input passes
    rig.rt.spin_for(1.0)
    rig.send(names.CMD_VEL_NAVIGATION, NAV)
    assert all(t == STILL for _, t in rig.out[first:])
    assert len([at for at, _ in rig.out if at > stopped_at]) >= 10  # held at zero meanwhile
    rig.estop("release")
    n = len(rig.out)
    rig.rt.spin_for(1.0)
    assert len(rig.out) == n  # released: nothing re-sent until a source publishes again
    rig.send(names.CMD_VEL_NAVIGATION, NAV)
    assert rig.last() == NAV


@pytest.mark.parametrize(
    ("text", "engaged"),
    [("stop", True), ("True", True), (" on ", True), ("1", True), ("release", False),
     ("false", False), ("0", False), ("", False)],
)  # fmt: skip
def test_one_parser_reads_the_stop_message(text: str, engaged: bool) -> None:
    assert estop_engaged(text) is engaged


def test_inputs_need_distinct_priorities() -> None:
    with pytest.raises(ValueError, match="distinct priorities"):
        VelocityMuxNode((MuxInput("a", "/a", 1), MuxInput("b", "/b", 1)))
