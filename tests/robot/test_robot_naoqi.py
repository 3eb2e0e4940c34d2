"""Pepper over NAOqi against fake NAOqi services in a standalone qi session on loopback."""

from __future__ import annotations

import itertools
import time
from collections.abc import Callable

import pytest
from naoqi_fakes import Recorder

from amiro.core.clock import SimClock
from amiro.core.config import ConfigError
from amiro.core.messages import Header, JointState, Odometry, SpeechRequest, String, Twist
from amiro.core.runtime import Runtime
from amiro.robot.naoqi_adapter import NaoqiRobotNode
from amiro.robot.naoqi_session import NaoqiSession
from amiro.robot.profile import load_profile


def _run_until(runtime: Runtime, done: Callable[[], bool], seconds: float = 5.0) -> None:
    deadline = time.monotonic() + seconds
    while not done() and time.monotonic() < deadline:
        runtime.spin_for(0.05)


def test_bus_topics_become_naoqi_calls(fake_pepper: tuple[str, Recorder]) -> None:
    url, rec = fake_pepper
    naoqi = NaoqiSession(url)
    runtime = Runtime(SimClock(speed=1.0))
    node = runtime.add(NaoqiRobotNode(naoqi, load_profile("pepper")))
    odoms: list[Odometry] = []
    runtime.bus.subscribe("/odom", Odometry, odoms.append)
    runtime.start()
    _run_until(runtime, lambda: node.languages is not None)
    bus = runtime.bus
    bus.publisher("/amiro/say", SpeechRequest).publish(SpeechRequest("Bonjour Marie", lang="fr"))
    bus.publisher("/amiro/say", SpeechRequest).publish(SpeechRequest("Salut", lang="ro"))
    bus.publisher("/amiro/display", String).publish(String("https://example.org/menu"))
    bus.publisher("/amiro/display", String).publish(String(""))
    bus.publisher("/amiro/head/cmd", JointState).publish(
        JointState(Header(), ("HeadYaw", "HeadPitch"), (0.3, 1.5))
    )
    bus.publisher("/amiro/posture", String).publish(String("Crouch"))
    cmd = bus.publisher("/cmd_vel", Twist)
    for _ in range(15):
        cmd.publish(Twist.planar(2.0, 0.0, 0.0))  # beyond Pepper's 0.35 m/s
        runtime.spin_for(0.1)
    _run_until(runtime, lambda: len(odoms) > 2 and len(rec.named("say")) == 2)
    runtime.stop()
    _run_until(runtime, lambda: bool(rec.named("stopMove")), 2.0)
    naoqi.close()

    assert rec.named("wakeUp") == [()]
    assert rec.named("goToPosture") == [
        ("Stand", pytest.approx(0.5)),
        ("Crouch", pytest.approx(0.5)),
    ]
    # Romanian is not installed on this robot: spoken with the default voice instead.
    assert rec.named("say") == [("Bonjour Marie", "French"), ("Salut", "English")]
    pages = [c[0] for c in rec.named("showWebview")]
    assert pages[0].startswith("data:text/html") and "Bonjour%20Marie" in pages[0]
    assert "https://example.org/menu" in pages and rec.named("hideWebview") == [()]
    [(names, angles, _speed)] = rec.named("setAngles")
    assert names == ["HeadYaw", "HeadPitch"] and angles == [
        pytest.approx(0.3),
        pytest.approx(0.6371),
    ]
    moves = rec.named("move")
    assert max(m[0] for m in moves) == pytest.approx(0.35, rel=1e-4)  # clamped to the profile
    assert all(b[0] - a[0] <= 0.5 / 10 + 1e-6 for a, b in itertools.pairwise(moves))
    assert moves[0][0] == pytest.approx(0.05, rel=1e-4)  # ramped from rest
    assert rec.named("stopMove") == [()]
    assert odoms[-1].pose.position.x == 1.0 and odoms[-1].twist.angular.z == pytest.approx(0.2)
    assert (odoms[-1].header.frame_id, odoms[-1].child_frame_id) == ("odom", "base_footprint")
    assert naoqi.errors == 0


def test_unreachable_robot_and_missing_service_are_one_line_errors(
    fake_pepper: tuple[str, Recorder],
) -> None:
    with pytest.raises(ConfigError, match=r"cannot reach NAOqi at tcp://127\.0\.0\.1:1"):
        NaoqiSession("tcp://127.0.0.1:1")
    naoqi = NaoqiSession(fake_pepper[0])
    with pytest.raises(ConfigError, match="has no ALAnimatedSpeech"):
        naoqi.service("ALAnimatedSpeech")
    naoqi.close()


def test_channels_left_to_another_adapter_are_not_touched(
    fake_pepper: tuple[str, Recorder],
) -> None:
    url, rec = fake_pepper
    naoqi = NaoqiSession(url)
    runtime = Runtime(SimClock(speed=1.0))
    runtime.add(NaoqiRobotNode(naoqi, load_profile("pepper"), handles=("say", "head")))
    runtime.start()
    runtime.bus.publisher("/cmd_vel", Twist).publish(Twist.planar(0.2, 0.0, 0.0))
    runtime.bus.publisher("/amiro/say", SpeechRequest).publish(SpeechRequest("Hello"))
    _run_until(runtime, lambda: bool(rec.named("say")))
    runtime.spin_for(0.3)
    runtime.stop()
    naoqi.close()
    assert rec.named("say") == [("Hello", "English")]
    assert not rec.named("move") and not rec.named("wakeUp") and not rec.named("showWebview")
    assert not rec.named("goToPosture")
