"""The simulator nodes on the bus: commands in, odometry, scans, joints, events out."""

from __future__ import annotations

import math

import pytest

from amiro.core import names
from amiro.core.config import ConfigError
from amiro.core.messages import Header, JointState, LaserScan, Odometry, Pose2D, String, Twist
from amiro.core.runtime import Runtime
from amiro.sim.config import SimConfig
from amiro.sim.messages import Collision
from amiro.sim.simulator import build_sim


def test_sim_drives_publishes_and_collides() -> None:
    rt = Runtime(seed=1)
    sim = build_sim(rt, SimConfig())
    assert sim.robot.true_pose == sim.world.place("dock")
    odoms: list[Odometry] = []
    scans: list[LaserScan] = []
    hits: list[Collision] = []
    truth: list[Pose2D] = []
    rt.bus.subscribe("/odom", Odometry, odoms.append, depth=1000)
    rt.bus.subscribe("/scan", LaserScan, scans.append, depth=1000)
    rt.bus.subscribe("/amiro/sim/collision", Collision, hits.append)
    rt.bus.subscribe("/amiro/sim/ground_truth", Pose2D, truth.append, depth=1000)
    cmd = rt.bus.publisher("/cmd_vel", Twist)
    rt.start()
    # drive +x towards the x=3 wall, re-sending the command like a controller would
    for _ in range(100):
        cmd.publish(Twist.planar(0.35, 0.0, 0.0))
        rt.spin_for(0.1)
    assert len(odoms) == pytest.approx(200, abs=2)  # 20 Hz
    assert len(scans) == pytest.approx(100, abs=2)  # 10 Hz
    assert odoms[-1].header.frame_id == "odom" and odoms[-1].child_frame_id == "base_footprint"
    assert sim.robot.collisions == 1 and len(hits) == 1
    assert sim.robot.true_pose.x + 0.25 <= 2.95 + 1e-9
    assert odoms[-1].pose.position.x == pytest.approx(sim.robot.true_pose.x - 0.8, abs=0.1)
    assert truth[-1] == sim.robot.true_pose
    assert scans[-1].ranges[180] < 0.5  # the wall right ahead


def test_cmd_timeout_head_and_emergency_stop() -> None:
    rt = Runtime(seed=2)
    sim = build_sim(rt, SimConfig(start="living_room"))
    joints: list[JointState] = []
    rt.bus.subscribe("/joint_states", JointState, joints.append, depth=100)
    rt.start()
    rt.bus.publish("/cmd_vel", Twist.planar(0.2, 0.0, 0.0))
    rt.spin_for(2.0)  # a single command times out after 0.5 s
    assert sim.robot.base.velocity == (0.0, 0.0, 0.0)
    assert 0.05 < sim.robot.true_pose.x - 5.0 < 0.15
    rt.bus.publish("/amiro/head/cmd", JointState(Header(), ("HeadYaw", "HeadPitch"), (1.0, 0.3)))
    rt.spin_for(1.0)
    assert sim.robot.head_yaw == pytest.approx(1.0) and sim.robot.head_pitch == pytest.approx(0.3)
    assert joints[-1].name == ("HeadYaw", "HeadPitch")
    assert joints[-1].position == pytest.approx((1.0, 0.3))
    rt.bus.publish(names.EMERGENCY_STOP, String("stop"))
    x0 = sim.robot.true_pose.x
    for _ in range(10):
        rt.bus.publish("/cmd_vel", Twist.planar(0.3, 0.0, 0.0))
        rt.spin_for(0.1)
    assert sim.robot.true_pose.x == x0


def test_same_seed_same_run() -> None:
    def run(seed: int) -> tuple[Pose2D, float]:
        rt = Runtime(seed=seed)
        sim = build_sim(rt, SimConfig(start="living_room"))
        rt.start()
        for _ in range(30):
            rt.bus.publish("/cmd_vel", Twist.planar(0.2, 0.1, 0.5))
            rt.spin_for(0.1)
        assert sim.robot.last_scan is not None
        return sim.robot.odom_pose, float(sim.robot.last_scan.ranges[90])

    assert run(5) == run(5)
    assert run(5) != run(6)


def test_config_overrides_and_errors() -> None:
    rt = Runtime()
    cfg = SimConfig.model_validate(
        {
            "start": {"x": 5.0, "y": 2.0, "theta": math.pi},
            "doors": {"bedroom_door": False},
            "obstacles": [{"name": "box", "polygon": [[6, 2], [6.4, 2], [6.4, 2.4]]}],
            "lidar": {"rate": 5.5},
        }
    )
    sim = build_sim(rt, cfg)
    assert sim.world.doors["bedroom_door"] is False and "box" in sim.world.obstacles
    assert sim.robot.true_pose == Pose2D(5.0, 2.0, math.pi)
    with pytest.raises(ConfigError, match="no_door"):
        build_sim(Runtime(), SimConfig(doors={"no_door": True}))
    with pytest.raises(ConfigError, match="attic"):
        build_sim(Runtime(), SimConfig(start="attic"))
    with pytest.raises(ValueError):
        SimConfig.model_validate({"lidar": {"rate": 30}})
    with pytest.raises(ValueError):
        SimConfig.model_validate({"residents": [{"name": "x"}]})  # neither at nor pose
