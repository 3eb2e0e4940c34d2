"""``/amiro/emergency_stop`` halts the simulated base, whoever is driving it, in the home.

"Within one control tick" is one physics step of the simulator (``sim.physics_rate``,
20 Hz): the base's velocity only changes when the simulator integrates it, so no stop can
act faster, and it is the period at which the robot adapter applies ``/cmd_vel``.  (The
behaviour engine's tick has the same 0.05 s by default, but a task's tick is not where the
base moves.)  Each case stops the base while it is moving, steps exactly one physics
period, and requires the true velocity to be zero then and the true pose to stay put.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import pytest

from amiro.behavior.graph import TaskGraph
from amiro.behavior.task import Task, make_task
from amiro.core import names
from amiro.core.bus import Bus
from amiro.core.messages import String
from amiro.core.node import Node
from amiro.navigation.primitives import ForwardGoal
from amiro.robot.velocity_mux import VelocityMuxNode
from amiro.scenarios.hydration import HydrationOptions, scenario_config
from amiro.sim.config import PoseSpec
from amiro.system import System, build_system


def _home(seed: int, trigger: bool = True, start: PoseSpec | None = None) -> System:
    cfg = scenario_config(HydrationOptions(seed=seed))
    if not trigger:
        env = cfg.environment.model_copy(update={"rules": ()})
        cfg = cfg.model_copy(update={"environment": env})
    if start is not None:
        cfg = cfg.model_copy(update={"sim": cfg.sim.model_copy(update={"start": start})})
    system = build_system(cfg)
    system.start()
    return system


def _speed(system: System) -> float:
    assert system.sim is not None
    vx, vy, wz = system.sim.robot.base.velocity
    return math.hypot(vx, vy) + abs(wz)


def _stop_and_check(system: System) -> None:
    """Engage the stop while the base moves; one physics step later it is still, and stays."""
    sim = system.sim
    assert sim is not None
    assert _speed(system) > 0.05, "the base should be moving when the stop is pressed"
    system.runtime.bus.publish(names.EMERGENCY_STOP, String("stop"))
    system.runtime.spin_for(1.0 / sim.config.physics_rate)
    assert sim.robot.base.velocity == (0.0, 0.0, 0.0)
    held = sim.robot.true_pose
    system.runtime.spin_for(3.0)  # the driving source keeps trying: nothing moves
    assert sim.robot.true_pose == held
    assert sim.robot.base.velocity == (0.0, 0.0, 0.0)


@contextmanager
def _cmd_vel_writers(bus: Bus) -> Iterator[set[str]]:
    """Who publishes on ``/cmd_vel``: the nearest node or task up the caller's stack."""
    writers: set[str] = set()
    publish = bus.publish

    def spy(name: str, msg: object) -> None:
        if name == names.CMD_VEL:
            frame = sys._getframe(1)
            while frame is not None:
                owner: Any = frame.f_locals.get("self")
                if isinstance(owner, Node | Task):
                    writers.add(type(owner).__name__)
                    break
                frame = frame.f_back  # type: ignore[assignment]
        publish(name, msg)

    bus.publish = spy  # type: ignore[method-assign]
    try:
        yield writers
    finally:
        bus.publish = publish  # type: ignore[method-assign]


def test_stop_during_recognize_activity_reframing() -> None:
    system = _home(seed=1)  # hydration: the robot reframes maria before recognising
    rt = system.runtime
    with _cmd_vel_writers(rt.bus) as writers:

        def reframing() -> bool:
            current = system.engine.current()
            return (
                current is not None
                and current["type"] == "RecognizeActivity"
                and (_speed(system) > 0.05)
            )

        assert rt.spin_until(reframing, 120.0), "hydration never reframed"
        _stop_and_check(system)
    assert writers == {VelocityMuxNode.__name__}


def test_stop_during_move_to() -> None:
    system = _home(seed=3, trigger=False)
    rt = system.runtime
    with _cmd_vel_writers(rt.bus) as writers:
        run = system.engine.submit(
            TaskGraph("go", 1).add("go", make_task("MoveTo", {"target": "kitchen"}))
        )
        assert rt.spin_until(lambda: _speed(system) > 0.2, 30.0)
        _stop_and_check(system)
        assert not run.done  # held, not failed
    assert writers == {VelocityMuxNode.__name__}


@pytest.mark.parametrize("distance", [1.0, -0.6])
def test_stop_during_a_forward_primitive(distance: float) -> None:
    # the hallway, facing along it: free ahead and behind
    system = _home(seed=3, trigger=False, start=PoseSpec(x=3.0, y=4.2, theta=0.0))
    rt = system.runtime
    with _cmd_vel_writers(rt.bus) as writers:
        rt.spin_for(0.2)  # first odometry and scan
        handle = rt.bus.send_goal(names.FORWARD, ForwardGoal(distance))
        assert rt.spin_until(lambda: _speed(system) > 0.1, 5.0)
        _stop_and_check(system)
        assert not handle.done
    assert writers == {VelocityMuxNode.__name__}
