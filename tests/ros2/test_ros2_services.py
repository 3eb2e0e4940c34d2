"""Services across two runtimes over real DDS; the server runs in a thread of its own, as
it would in its own process, since a service call blocks the caller's thread."""

from __future__ import annotations

import threading
from collections.abc import Iterator
from dataclasses import dataclass

import pytest

from amiro.core.clock import SimClock
from amiro.core.messages import Point
from amiro.core.node import Node
from amiro.core.runtime import Runtime
from amiro.ros2.bridge import Ros2Bridge
from amiro.ros2.context import RosContext
from amiro.ros2.interfaces import service_spec
from amiro.ros2.services import RemoteService, RemoteServiceError, ServiceExporter

NEAREST = "/test/nearest"


@dataclass(frozen=True)
class NearestRequest:
    origin: Point
    candidates: tuple[Point, ...]


@dataclass(frozen=True)
class NearestResponse:
    index: int
    point: Point


class NearestService(Node):
    def __init__(self) -> None:
        super().__init__("nearest")

    def on_start(self) -> None:
        self.create_service(NEAREST, self.nearest)

    def nearest(self, req: NearestRequest) -> NearestResponse:
        if not req.candidates:
            raise ValueError("no candidates")
        dist = [(p.x - req.origin.x) ** 2 + (p.y - req.origin.y) ** 2 for p in req.candidates]
        best = dist.index(min(dist))
        return NearestResponse(best, req.candidates[best])


SPEC = service_spec(NEAREST, NearestRequest, NearestResponse, timeout_s=3.0)


@pytest.fixture
def caller(domain_id: int) -> Iterator[tuple[Runtime, RemoteService]]:
    a, b = RosContext("amiro_test_caller", domain_id), RosContext("amiro_test_server", domain_id)
    server = Runtime(SimClock(speed=1.0))
    server.add(Ros2Bridge(b))
    server.add(NearestService())
    exporter = server.add(ServiceExporter(b, SPEC))
    stop = threading.Event()

    def serve() -> None:
        server.start()
        while not stop.is_set():
            server.spin_for(0.01)
        server.stop()

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    client = Runtime(SimClock(speed=1.0))
    remote = client.add(RemoteService(a, SPEC))
    client.start()
    assert not a.wait_for_nodes(["amiro_test_server"], 10.0)
    yield client, remote
    stop.set()
    thread.join(5.0)
    assert exporter.stats.errors == 0
    client.stop()
    a.close()
    b.close()


def test_a_remote_service_answers_a_call_on_the_local_bus(
    caller: tuple[Runtime, RemoteService],
) -> None:
    client, remote = caller
    request = NearestRequest(Point(0.0, 0.0), (Point(3.0, 4.0), Point(1.0, -1.0), Point(5.0, 0.0)))
    answer = client.bus.call(NEAREST, request)
    assert answer == NearestResponse(1, Point(1.0, -1.0))
    # a second call, with an answer that differs, proves responses are matched to calls
    assert client.bus.call(NEAREST, NearestRequest(Point(5.0, 1.0), request.candidates)).index == 2
    assert remote.stats.sent == 2 and remote.stats.received == 2


def test_a_remote_failure_is_raised_to_the_caller(caller: tuple[Runtime, RemoteService]) -> None:
    client, _ = caller
    with pytest.raises(RemoteServiceError, match="ValueError: no candidates"):
        client.bus.call(NEAREST, NearestRequest(Point(), ()))


def test_a_call_without_a_server_times_out(domain_id: int) -> None:
    ros = RosContext("amiro_test_lonely", domain_id)
    client = Runtime(SimClock(speed=1.0))
    client.add(RemoteService(ros, service_spec(NEAREST, NearestRequest, NearestResponse, 0.3)))
    client.start()
    with pytest.raises(RemoteServiceError, match=r"no answer within 0.3 s"):
        client.bus.call(NEAREST, NearestRequest(Point(), ()))
    client.stop()
    ros.close()
