"""Forward / rotate primitives in the simulated apartment: accuracy, cancel, e-stop, blocked."""

from __future__ import annotations

import math
from typing import Any

import pytest

from amiro.core import names
from amiro.core.bus import GoalHandle, GoalStatus
from amiro.core.clock import SimClock
from amiro.core.geometry import wrap_angle
from amiro.core.messages import String
from amiro.core.runtime import Runtime
from amiro.navigation.poses import between
from amiro.navigation.primitives import ForwardGoal, PrimitiveResult, PrimitivesNode, RotateGoal
from amiro.robot.velocity_mux import VelocityMuxNode
from amiro.sim.config import PoseSpec, SimConfig
from amiro.sim.simulator import Simulation, build_sim

# the hallway, facing along it (free for about 3 m ahead)
START = PoseSpec(x=2.0, y=4.2, theta=0.0)


def _rig(start: PoseSpec = START) -> tuple[Runtime, Simulation]:
    rt = Runtime(SimClock(), seed=0)
    sim = build_sim(rt, SimConfig(start=start))
    rt.add(PrimitivesNode())
    rt.add(VelocityMuxNode())
    rt.start()
    rt.spin_for(0.2)  # first odometry and lidar scan
    return rt, sim


def _run(rt: Runtime, handle: GoalHandle[Any, Any, Any], timeout: float = 30.0) -> PrimitiveResult:
    assert rt.spin_until(lambda: handle.done, timeout)
    assert isinstance(handle.result, PrimitiveResult)
    return handle.result


def test_forward_then_rotate_reach_their_targets() -> None:
    rt, sim = _rig()
    start = sim.robot.true_pose
    fwd = rt.bus.send_goal(names.FORWARD, ForwardGoal(1.0))
    assert _run(rt, fwd).reason == "done"
    assert fwd.status is GoalStatus.SUCCEEDED
    moved = between(start, sim.robot.true_pose)
    assert moved.x == pytest.approx(1.0, abs=0.05) and abs(moved.y) < 0.05
    before = sim.robot.true_pose
    rot = rt.bus.send_goal(names.ROTATE, RotateGoal(-math.pi / 2))
    _run(rt, rot)
    assert rot.status is GoalStatus.SUCCEEDED
    turned = wrap_angle(sim.robot.true_pose.theta - before.theta)
    assert turned == pytest.approx(-math.pi / 2, abs=0.05)
    assert sim.robot.true_pose.distance_to(before) < 0.05
    assert sim.robot.collisions == 0


def test_cancel_stops_part_way() -> None:
    rt, sim = _rig()
    handle = rt.bus.send_goal(names.FORWARD, ForwardGoal(2.0))
    rt.spin_for(2.0)
    handle.cancel()
    result = _run(rt, handle)
    assert handle.status is GoalStatus.CANCELED
    assert 0.1 < result.achieved < 1.0
    rt.spin_for(1.0)
    vx, vy, wz = sim.robot.base.velocity
    assert math.hypot(vx, vy) < 1e-6 and abs(wz) < 1e-6


def test_emergency_stop_holds_the_motion_until_released() -> None:
    rt, sim = _rig()
    estop = rt.bus.publisher(names.EMERGENCY_STOP, String)
    handle = rt.bus.send_goal(names.ROTATE, RotateGoal(math.pi))
    rt.spin_for(0.5)
    estop.publish(String("true"))
    rt.spin_for(0.5)
    held = sim.robot.true_pose.theta
    rt.spin_for(2.0)
    assert not handle.done
    assert abs(wrap_angle(sim.robot.true_pose.theta - held)) < 1e-6
    estop.publish(String("false"))
    result = _run(rt, handle)
    assert handle.status is GoalStatus.SUCCEEDED
    assert result.achieved == pytest.approx(math.pi, abs=0.02)


def test_driving_into_a_wall_fails_blocked_without_touching_it() -> None:
    rt, sim = _rig()
    handle = rt.bus.send_goal(names.FORWARD, ForwardGoal(-3.0))  # the wall is ~1.5 m behind
    result = _run(rt, handle, 60.0)
    assert handle.status is GoalStatus.ABORTED and result.reason == "blocked"
    assert -3.0 < result.achieved < 0.0
    assert sim.robot.collisions == 0


def test_bad_goals_are_rejected() -> None:
    rt, _ = _rig()
    handle = rt.bus.send_goal(names.ROTATE, RotateGoal(math.nan))
    rt.spin_for(0.1)
    assert handle.status is GoalStatus.REJECTED


def test_a_forward_goal_may_ask_for_a_lower_speed_never_a_bad_one() -> None:
    rt, sim = _rig()
    speeds: list[float] = []
    rt.create_timer(0.05, lambda: speeds.append(abs(sim.robot.base.velocity[0])))
    handle = rt.bus.send_goal(names.FORWARD, ForwardGoal(0.5, speed=0.1))
    assert _run(rt, handle).reason == "done"
    assert max(speeds) == pytest.approx(0.1, abs=1e-6)  # the node alone would go at 0.2
    for speed in (0.0, -0.1, math.nan):
        assert rt.bus.send_goal(names.FORWARD, ForwardGoal(0.5, speed)).status is (
            GoalStatus.REJECTED
        )
