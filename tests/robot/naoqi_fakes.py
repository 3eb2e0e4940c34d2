"""Fake NAOqi services: what Pepper's ALTextToSpeech, ALTabletService, ALMotion and
ALRobotPosture look like over qi, recording every call they receive."""

from __future__ import annotations

import threading
from typing import Any

import qi


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
