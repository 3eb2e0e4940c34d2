"""The edge's head-sensor feed, without ROS: the robot side's publisher and the feed on one bus
give perception and activity what the simulator gives them in one process."""

from __future__ import annotations

import math

import numpy as np
import pytest

from amiro.activity.onnx_model import ActivityModel
from amiro.activity.recognizer import SkeletonActivityRecognizer
from amiro.core import names
from amiro.core.clock import SimClock
from amiro.core.messages import Header, Odometry, Pose2D, Skeleton, Twist
from amiro.core.runtime import Runtime
from amiro.deploy.boundary import CameraObservations, HeadSensorsFeed, HeadSensorsPublisher
from amiro.perception.config import PerceptionConfig
from amiro.perception.stack import SimPeopleFinder
from amiro.sim.config import SimConfig
from amiro.sim.simulator import Simulation, build_sim
from amiro.sim.skeletons import SkeletonCamera

MARIA = (7.0, 2.1)


def _scene(activity: str = "idle") -> tuple[Runtime, Simulation, SkeletonCamera, HeadSensorsFeed]:
    cfg = SimConfig.model_validate(
        {
            "start": {"x": 4.0, "y": 2.0, "theta": 0.0},
            "residents": [
                {"name": "ion", "pose": {"x": 1.0, "y": 1.0, "theta": 0.0}},  # out of view
                {
                    "name": "maria",
                    "pose": {"x": MARIA[0], "y": MARIA[1], "theta": math.pi},
                    "activity": activity,
                },
            ],
        }
    )
    runtime = Runtime(SimClock(), seed=2)
    sim = build_sim(runtime, cfg)
    skeletons = SkeletonCamera(sim, np.random.default_rng(0))
    runtime.add(HeadSensorsPublisher(sim, skeletons))
    feed = HeadSensorsFeed(
        runtime.bus,
        sim.camera_mount(),
        sim.household(),
        sim.robot_pose,
        cfg.skeletons.pitch_deg,
    )
    runtime.start()
    return runtime, sim, skeletons, feed


def test_before_the_robot_reports_nothing_is_seen_or_guessed() -> None:
    runtime = Runtime(SimClock(), seed=0)
    feed = HeadSensorsFeed(runtime.bus, (1.15, 0.08), ("maria",), lambda: None)
    finder = SimPeopleFinder(feed, np.random.default_rng(0), PerceptionConfig())
    assert finder.look() == [] and finder.estimates == 0
    assert feed.window("maria", 30) is None and feed.framing("maria") is None
    assert feed.head_joints() is None and feed.robot_pose() is None


def test_the_feed_offers_the_simulators_frame_intrinsics_and_head_joints() -> None:
    runtime, sim, _, feed = _scene()
    runtime.spin_for(1.0)
    assert feed.received["frames"] >= 9 and feed.received["joint_states"] >= 19
    assert [o.name for o in feed.observe()] == ["maria"]
    info, truth = feed.camera_info(), sim.camera_info()
    assert info is not None and (info.width, info.height, info.k) == (
        truth.width,
        truth.height,
        truth.k,
    )
    assert feed.head_joints() == pytest.approx(sim.head_joints())
    assert feed.household() == ("ion", "maria")
    assert feed.framing("maria") == SkeletonCamera(sim, np.random.default_rng(0)).framing("maria")


def test_the_people_finder_places_maria_from_the_fed_frames() -> None:
    runtime, _, _, feed = _scene()
    runtime.spin_for(0.5)
    finder = SimPeopleFinder(feed, np.random.default_rng(1), PerceptionConfig())
    seen = []
    for _ in range(10):
        runtime.spin_for(0.1)
        seen += [p for p in finder.look() if p.name == "maria"]
    assert seen and finder.estimates >= 8
    assert math.hypot(seen[-1].position.x - MARIA[0], seen[-1].position.y - MARIA[1]) < 0.25


def test_fed_skeletons_match_the_skeleton_camera_even_while_the_robot_turns() -> None:
    runtime, _, skeletons, feed = _scene()
    runtime.spin_for(1.0)
    turn = runtime.bus.publisher("/cmd_vel", Twist)
    for _ in range(10):  # the robot turns; the person stands still
        turn.publish(Twist.planar(0.0, 0.0, 0.3))
        runtime.spin_for(0.1)
    fed = feed.window("maria", 30)
    direct = skeletons.window("maria", 30)
    assert fed is not None and direct is not None and fed.shape == (30, 25, 3)
    assert feed.received["skeletons"] >= 60  # the camera's history, then 15 frames a second
    seen = ~np.isnan(direct)
    assert np.array_equal(seen, ~np.isnan(fed))
    assert np.allclose(fed[seen], direct[seen], atol=0.03)


def test_the_activity_model_recognises_drinking_on_fed_skeletons() -> None:
    runtime, _, _, feed = _scene(activity="drink_water")
    runtime.spin_for(3.0)
    recognizer = SkeletonActivityRecognizer(feed, ActivityModel(None))
    reading = recognizer.observe("maria")
    assert reading.skeleton_complete and reading.label == "drink_water"
    assert recognizer.observe("ion").label is None  # out of view: no skeletons, no guess


def test_a_body_the_household_does_not_explain_is_dropped() -> None:
    runtime, _, _, feed = _scene()
    runtime.spin_for(0.5)
    before = dict(feed.bodies)
    stranger = Skeleton(Header(0.5, "camera_level"), 7, np.zeros((25, 3)), np.ones(25, bool))
    runtime.bus.publisher(names.SKELETONS, Skeleton).publish(stranger)
    runtime.spin_for(0.1)
    assert set(feed.bodies) == set(before) == {"maria"}


def test_the_pose_of_a_late_frame_is_carried_back_by_odometry() -> None:
    runtime = Runtime(SimClock(), seed=0)
    estimate = Pose2D(5.0, 1.0, math.pi / 2)  # localisation now, in the map
    feed = HeadSensorsFeed(runtime.bus, (1.15, 0.08), ("maria",), lambda: estimate)
    odom = runtime.bus.publisher(names.ODOM, Odometry)
    for stamp, x in ((1.0, 0.0), (2.0, 0.5)):  # drove 0.5 m forward between the two
        pose = Pose2D(x, 0.0, 0.0).to_pose()
        odom.publish(Odometry(Header(stamp, "odom"), "base_footprint", pose, Twist()))
    frame = runtime.bus.publisher(names.OBSERVATIONS, CameraObservations)
    frame.publish(CameraObservations(1.0, ()))  # taken at 1.0, heard now
    runtime.spin_for(0.05)
    then = feed.robot_pose()
    assert then is not None
    assert (then.x, then.y, then.theta) == pytest.approx((5.0, 0.5, math.pi / 2))
