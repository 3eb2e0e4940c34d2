"""Robot-adapter tests talk ROS 2 on loopback in domains of their own, or NAOqi on loopback."""

from __future__ import annotations

from collections.abc import Iterator

import pytest
import qi
from naoqi_fakes import FakeMotion, FakePosture, FakeTablet, FakeTTS, Recorder

from amiro.ros2.env import claimed_domain


@pytest.fixture
def robot_domain() -> Iterator[int]:
    with claimed_domain() as domain:
        yield domain


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
