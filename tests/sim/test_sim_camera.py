"""The head camera: projection, occlusion, field of view, head motion, face cues."""

from __future__ import annotations

import math

import numpy as np
import pytest

from amiro.core.messages import Pose2D
from amiro.home.world import World, default_home_path
from amiro.robot.camera import Camera
from amiro.sim.camera import HEAD_YAW_LIMITS, Head, observe_residents
from amiro.sim.residents import Resident


@pytest.fixture(scope="module")
def world() -> World:
    return World.load(default_home_path())


def rng() -> np.random.Generator:
    return np.random.default_rng(0)


def test_intrinsics_from_fov() -> None:
    cam = Camera()
    info = cam.info(0.0)
    assert (info.width, info.height) == (640, 480)
    assert info.cx == 320 and info.cy == 240
    assert 2 * math.degrees(math.atan(320 / info.fx)) == pytest.approx(55.2)
    assert 2 * math.degrees(math.atan(240 / info.fy)) == pytest.approx(44.3)


def test_resident_straight_ahead(world: World) -> None:
    robot = Pose2D(4.0, 2.0, 0.0)  # living room, facing +x
    alice = Resident("alice", 4.08 + 3.0, 2.0, heading=math.pi)
    (obs,) = observe_residents(Camera(), world, robot, 0.0, 0.0, [alice], rng())
    assert obs.name == "alice"
    assert obs.bbox.cx == pytest.approx(320, abs=1.0)
    assert obs.depth == pytest.approx(3.0, abs=0.05)
    assert obs.face_visible and not obs.backlit
    assert obs.position.x == pytest.approx(7.08) and obs.position.z == pytest.approx(0.85)
    # a standing person 3 m away spans most of the image height but not all of it
    assert 250 < obs.bbox.height < 480


def test_posture_changes_the_box(world: World) -> None:
    robot = Pose2D(4.0, 2.0, 0.0)
    standing = Resident("a", 7.08, 2.0, heading=math.pi)
    sitting = Resident("a", 7.08, 2.0, heading=math.pi, posture="sitting_couch")
    lying = Resident("a", 7.08, 2.0, heading=math.pi / 2, posture="lying_couch")
    cam = Camera()
    h = {
        r.posture: observe_residents(cam, world, robot, 0.0, 0.0, [r], rng())[0].bbox
        for r in (standing, sitting, lying)
    }
    assert h["standing"].height > h["sitting_couch"].height > h["lying_couch"].height
    assert h["lying_couch"].width > 2 * h["standing"].width


def test_behind_wall_out_of_fov_and_head_turn(world: World) -> None:
    cam = Camera()
    robot = Pose2D(2.0, 2.0, 0.0)  # hallway; the living room is behind the x=3 wall
    bob = Resident("bob", 5.0, 2.0)
    assert observe_residents(cam, world, robot, 0.0, 0.0, [bob], rng()) == []
    robot = Pose2D(5.0, 2.0, 0.0)  # in the living room, carol 1.2 m to the left
    carol = Resident("carol", 5.0, 3.2)
    assert observe_residents(cam, world, robot, 0.0, 0.0, [carol], rng()) == []
    head = Head()
    head.command(yaw=math.pi / 2)
    for _ in range(10):
        head.step(0.05)
    assert head.yaw == pytest.approx(0.75)  # 1.5 rad/s max speed
    for _ in range(40):
        head.step(0.05)
    assert head.yaw == pytest.approx(math.pi / 2)
    seen = observe_residents(cam, world, robot, head.yaw, head.pitch, [carol], rng())
    assert [o.name for o in seen] == ["carol"]
    head.command(yaw=10.0)
    assert head.target_yaw == HEAD_YAW_LIMITS[1]


def test_low_furniture_does_not_hide_but_wardrobe_does(world: World) -> None:
    cam = Camera()
    robot = Pose2D(7.0, 2.6, -math.pi / 2)  # the couch place, facing the couch
    sitting = Resident("d", 7.0, 0.6, heading=math.pi / 2, posture="sitting_couch")
    (obs,) = observe_residents(
        cam, world, robot, 0.0, 0.0, [sitting], rng()
    )  # over the coffee table
    assert obs.face_visible
    assert obs.backlit  # the living-room window is right behind the couch
    fresh = World.load(default_home_path())
    robot, person = Pose2D(4.0, 2.0, 0.0), Resident("e", 6.0, 2.5, heading=math.pi)
    box = [(5.0, 2.0), (5.4, 2.0), (5.4, 2.6), (5.0, 2.6)]
    fresh.add_obstacle("box", box, 0.8)
    assert len(observe_residents(cam, fresh, robot, 0.0, 0.0, [person], rng())) == 1
    fresh.add_obstacle("box", box, 2.0)
    assert observe_residents(cam, fresh, robot, 0.0, 0.0, [person], rng()) == []


def test_face_away_and_absent(world: World) -> None:
    cam = Camera()
    robot = Pose2D(4.0, 2.0, 0.0)
    away = Resident("f", 7.0, 2.0, heading=0.0)  # looking away from the robot
    (obs,) = observe_residents(cam, world, robot, 0.0, 0.0, [away], rng())
    assert not obs.face_visible
    gone = Resident("g", 7.0, 2.0, present=False)
    assert observe_residents(cam, world, robot, 0.0, 0.0, [gone], rng()) == []


def test_depth_noise_grows_with_distance(world: World) -> None:
    cam = Camera()
    robot = Pose2D(3.3, 2.0, 0.0)
    g = np.random.default_rng(1)
    near = [
        observe_residents(cam, world, robot, 0.0, 0.0, [Resident("n", 4.4, 2.0)], g)[0].depth
        for _ in range(200)
    ]
    far = [
        observe_residents(cam, world, robot, 0.0, 0.0, [Resident("n", 9.4, 2.0)], g)[0].depth
        for _ in range(200)
    ]
    assert np.std(far) > 10 * np.std(near)
    assert np.std(far) == pytest.approx(1.4e-3 * 6.02**2, rel=0.2)
