"""The REP-105 frames amiro publishes: geometry against the simulator's own camera model,
and the nodes on an embedded bus (no ROS 2 needed)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from amiro.core import names
from amiro.core.clock import SimClock
from amiro.core.messages import (
    Header,
    JointState,
    Odometry,
    Pose2D,
    TransformStamped,
    Twist,
)
from amiro.core.runtime import Runtime
from amiro.deploy.tf import (
    OPTICAL,
    MapOdomNode,
    RobotFramesNode,
    head_camera,
    map_to_odom,
    robot_frames,
    transform,
)
from amiro.navigation.poses import compose
from amiro.robot.camera import Camera, CameraParams
from amiro.sim.config import SimConfig
from amiro.sim.simulator import build_sim


def _matrix(tf: TransformStamped) -> np.ndarray:
    """4x4 homogeneous matrix of ``child`` expressed in ``parent``."""
    q = tf.rotation
    out = np.eye(4)
    out[:3, :3] = Rotation.from_quat([q.x, q.y, q.z, q.w]).as_matrix()
    out[:3, 3] = [tf.translation.x, tf.translation.y, tf.translation.z]
    return out


@pytest.mark.parametrize(("yaw", "pitch"), [(0.0, 0.0), (0.7, 0.3), (-1.2, -0.25)])
def test_camera_frame_chain_matches_the_simulated_camera(yaw: float, pitch: float) -> None:
    """A point seen through base_link -> camera_link -> camera lands where the sim's camera
    model puts it in its optical frame (robot at the map origin, so map = base_link)."""
    params = CameraParams()
    optical = transform(0.0, "camera_link", params.frame_id, rotation=OPTICAL)
    base_to_optical = _matrix(head_camera(0.0, params, yaw, pitch)) @ _matrix(optical)
    points = np.array([[2.0, 0.5, 0.3], [1.0, -1.0, 1.5], [3.0, 2.0, 0.0]])
    homogeneous = np.c_[points, np.ones(len(points))]
    ours = (np.linalg.inv(base_to_optical) @ homogeneous.T).T[:, :3]
    theirs = Camera(params).to_optical(points, Pose2D(0.0, 0.0, 0.0), yaw, pitch)
    np.testing.assert_allclose(ours, theirs, atol=1e-9)


def test_map_to_odom_composed_with_odometry_is_the_map_pose() -> None:
    map_pose, odom_pose = Pose2D(3.0, 1.0, 2.0), Pose2D(-0.5, 0.8, -0.4)
    tf = map_to_odom(5.0, map_pose, odom_pose)
    assert (tf.header.frame_id, tf.child_frame_id, tf.header.stamp) == ("map", "odom", 5.0)
    correction = Pose2D(tf.translation.x, tf.translation.y, tf.rotation.yaw)
    back = compose(correction, odom_pose)
    assert (back.x, back.y, back.theta) == pytest.approx((map_pose.x, map_pose.y, map_pose.theta))


def test_robot_frames_publish_static_mounts_and_the_moving_head() -> None:
    rt = Runtime(SimClock(), seed=0)
    sim = build_sim(rt, SimConfig())
    node = rt.add(robot_frames(sim))
    statics: list[TransformStamped] = []
    dynamic: list[TransformStamped] = []
    rt.bus.subscribe(names.TF_STATIC, TransformStamped, statics.append, depth=100)
    rt.bus.subscribe("/tf", TransformStamped, dynamic.append, depth=1000)
    rt.start()
    sim.robot.head.command(0.5, 0.2)  # the head turns: its camera frame follows on /tf
    rt.spin_for(2.0)
    assert {(t.header.frame_id, t.child_frame_id) for t in statics} == {
        ("base_footprint", "base_link"),
        ("base_link", sim.robot.lidar.params.frame_id),
        ("camera_link", node.camera.frame_id),
    }
    heads = [t for t in dynamic if t.child_frame_id == "camera_link"]
    odoms = [t for t in dynamic if t.child_frame_id == "base_footprint"]
    assert len(odoms) == pytest.approx(40, abs=2)  # the simulator's odometry, 20 Hz
    assert len(heads) == pytest.approx(20, abs=2)  # the head, throttled to 10 Hz
    assert heads[0].header.frame_id == "base_link"
    assert heads[-1].rotation.yaw == pytest.approx(sim.robot.head_yaw, abs=1e-6)
    assert heads[-1].rotation.yaw > heads[0].rotation.yaw + 0.3
    assert heads[-1].translation.z == pytest.approx(node.camera.height)


def test_joint_states_without_head_joints_publish_nothing() -> None:
    rt = Runtime(SimClock(), seed=0)
    rt.add(RobotFramesNode("laser", CameraParams()))
    dynamic: list[TransformStamped] = []
    rt.bus.subscribe("/tf", TransformStamped, dynamic.append)
    rt.start()
    rt.bus.publish("/joint_states", JointState(Header(1.0, ""), ("Wheel",), (0.3,)))
    rt.bus.publish(
        "/joint_states", JointState(Header(1.0, ""), (names.HEAD_YAW, names.HEAD_PITCH), (0.1, 0))
    )
    rt.spin_for(0.1)
    assert [t.child_frame_id for t in dynamic] == ["camera_link"]


def test_map_odom_node_waits_for_odometry_then_follows_poses_at_10_hz() -> None:
    rt = Runtime(SimClock(), seed=0)
    rt.add(MapOdomNode("/pose"))
    out: list[TransformStamped] = []
    rt.bus.subscribe("/tf", TransformStamped, out.append)
    rt.start()
    rt.bus.publish("/pose", Pose2D(1.0, 2.0, 0.5))  # no odometry yet: nothing to correct
    rt.spin_for(0.1)
    assert out == []
    odom = Pose2D(0.4, -0.2, math.pi / 3)
    rt.bus.publish(
        "/odom", Odometry(Header(0.1, "odom"), "base_footprint", odom.to_pose(), Twist())
    )
    rt.spin_for(0.1)
    rt.bus.publish("/pose", Pose2D(1.0, 2.0, 0.5))
    rt.spin_for(0.05)
    rt.bus.publish("/pose", Pose2D(1.1, 2.0, 0.5))  # within the period: dropped
    rt.spin_for(0.01)
    assert len(out) == 1 and out[0] == map_to_odom(out[0].header.stamp, Pose2D(1.0, 2.0, 0.5), odom)
