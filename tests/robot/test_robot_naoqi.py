"""Pepper over NAOqi against fake NAOqi services in a standalone qi session on loopback."""

from __future__ import annotations

import itertools
import threading
import time
from collections.abc import Callable, Iterator
from typing import Any

import pytest
import qi

from amiro.core.clock import SimClock
from amiro.core.config import ConfigError
from amiro.core.messages import Header, JointState, Odometry, SpeechRequest, String, Twist
from amiro.core.runtime import Runtime
from amiro.robot.naoqi_adapter import NaoqiRobotNode
from amiro.robot.naoqi_session import NaoqiSession
from amiro.robot.profile import load_profile


class Recorder:
    """Every call a fake service received, in order (qi calls arrive on its own threads)."""

    def __init__(self) -> None:
        self.calls: list[tuple[Any, ...]] = []
        self.lock = threading.Lock()

    def add(self, *call: Any) -> None:
        with self.lock:
            self.calls.append(call)

    def named(self, name: str) -> list[tuple[Any, ...]]:
        with self.lock:
            return [c[1:] for c in self.calls if c[0] == name]


class FakeTTS:
    def __init__(self, rec: Recorder) -> None:
        self.rec = rec

    @qi.bind(qi.Void, (qi.String, qi.String))
    def say(self, text: str, language: str) -> None:
        self.rec.add("say", text, language)

    @qi.bind(qi.List(qi.String), ())
    def getAvailableLanguages(self) -> list[str]:  # noqa: N802 - NAOqi's name
        return ["English", "French"]


class FakeTablet:
    def __init__(self, rec: Recorder) -> None:
        self.rec = rec

    @qi.bind(qi.Bool, (qi.String,))
    def showWebview(self, url: str) -> bool:  # noqa: N802
        self.rec.add("showWebview", url)
        return True

    @qi.bind(qi.Bool, ())
    def hideWebview(self) -> bool:  # noqa: N802
        self.rec.add("hideWebview")
        return True


class FakeMotion:
    def __init__(self, rec: Recorder) -> None:
        self.rec = rec

    @qi.bind(qi.Void, ())
    def wakeUp(self) -> None:  # noqa: N802
        self.rec.add("wakeUp")

    @qi.bind(qi.Void, (qi.List(qi.String), qi.List(qi.Float), qi.Float))
    def setAngles(self, names: list[str], angles: list[float], speed: float) -> None:  # noqa: N802
        self.rec.add("setAngles", list(names), list(angles), speed)

    @qi.bind(qi.Void, (qi.Float, qi.Float, qi.Float))
    def move(self, x: float, y: float, theta: float) -> None:
        self.rec.add("move", x, y, theta)

    @qi.bind(qi.Void, ())
    def stopMove(self) -> None:  # noqa: N802
        self.rec.add("stopMove")

    @qi.bind(qi.List(qi.Float), (qi.Bool,))
    def getRobotPosition(self, use_sensors: bool) -> list[float]:  # noqa: N802
        return [1.0, 2.0, 0.5]

    @qi.bind(qi.List(qi.Float), ())
    def getRobotVelocity(self) -> list[float]:  # noqa: N802
        return [0.1, 0.0, 0.2]


class FakePosture:
    def __init__(self, rec: Recorder) -> None:
        self.rec = rec

    @qi.bind(qi.Bool, (qi.String, qi.Float))
    def goToPosture(self, name: str, speed: float) -> bool:  # noqa: N802
        self.rec.add("goToPosture", name, speed)
        return True


@pytest.fixture
def fake_pepper() -> Iterator[tuple[str, Recorder]]:
    """NAOqi's services on 127.0.0.1 (a free port), as a robot would offer them."""
    rec = Recorder()
    server = qi.Session()
    server.listenStandalone("tcp://127.0.0.1:0")
    services = {
        "ALTextToSpeech": FakeTTS(rec),
        "ALTabletService": FakeTablet(rec),
        "ALMotion": FakeMotion(rec),
        "ALRobotPosture": FakePosture(rec),
    }
    for name, obj in services.items():
        server.registerService(name, obj)
    yield server.endpoints()[0], rec
    server.close()


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
