"""Services across processes over a request/response topic pair with correlation ids.

No installed ROS 2 interface package has a generic string-in/string-out srv (std_srvs has
Trigger and SetBool only), so ``<service>/request`` and ``<service>/response`` carry JSON in
std_msgs/String: ``{"id", "request"}`` and ``{"id", "response"}`` or ``{"id", "error"}``.
:class:`RemoteService` registers on the caller's bus, so ``bus.call`` stays synchronous: it
spins ROS 2 until the answer comes.  That wait is measured on the wall clock, because the
runtime's clock does not move while its only thread is blocked in the call.
"""

from __future__ import annotations

import itertools
import os
import time
from typing import Any

from amiro.core.bus import BusError
from amiro.ros2.context import RosContext
from amiro.ros2.endpoint import WireEndpoint
from amiro.ros2.interfaces import ServiceSpec, WireError, envelope


class RemoteServiceError(BusError):
    """The remote service failed, or did not answer within its timeout."""


class ServiceExporter(WireEndpoint):
    """Server side: requests arriving over ROS 2 are answered by the local bus service."""

    def __init__(self, ros: RosContext, spec: ServiceSpec) -> None:
        super().__init__(ros, spec.name, f"ros2_serve:{spec.name}")
        self.spec = spec
        self.incoming("request")
        self.outgoing("response")

    def handle(self, kind: str, msg: Any) -> None:
        data = envelope(str(msg.data), "id", "request")
        call_id = data["id"]
        if not isinstance(call_id, str):
            raise WireError("id must be a string")
        request = self.spec.request.load(data["request"])
        try:
            response = self.runtime.bus.call(self.interface, request)
        except Exception as exc:  # the caller gets the error; this process carries on
            self.send("response", {"id": call_id, "error": f"{type(exc).__name__}: {exc}"})
            return
        self.send("response", {"id": call_id, "response": self.spec.response.dump(response)})


class RemoteService(WireEndpoint):
    """Client side: stands on the local bus for a service living in another process."""

    def __init__(self, ros: RosContext, spec: ServiceSpec) -> None:
        super().__init__(ros, spec.name, f"ros2_call:{spec.name}")
        self.spec = spec
        self.outgoing("request")
        # responses are read directly from ROS 2 while a call blocks, not via the bus
        ros.subscribe("std_msgs/msg/String", self.ros_topic("response"), self._on_response, 100)
        owner = f"{ros.node.get_fully_qualified_name()}/{os.getpid()}"
        self._ids = (f"{owner}/{n}" for n in itertools.count(1))
        self._waiting: str | None = None
        self._answer: dict[str, Any] | None = None

    def on_start(self) -> None:
        super().on_start()
        self.create_service(self.interface, self.call)

    def _on_response(self, msg: Any) -> None:
        if self._waiting is None:
            return  # an answer to a call that timed out, or to another client
        try:
            data = envelope(str(msg.data), "id")
        except WireError as exc:
            self.stats.errors += 1
            self.log.warning("bad response on %s dropped: %s", self.interface, exc)
            return
        if data["id"] == self._waiting:
            self._answer = data

    def call(self, request: Any) -> Any:
        call_id = next(self._ids)
        self._waiting, self._answer = call_id, None
        self.send("request", {"id": call_id, "request": self.spec.request.dump(request)})
        deadline = time.monotonic() + self.spec.timeout_s
        try:
            while self._answer is None and time.monotonic() < deadline:
                self.ros.spin(0.01)
        finally:
            answer, self._waiting = self._answer, None
        if answer is None:
            raise RemoteServiceError(
                f"service {self.interface}: no answer within {self.spec.timeout_s:g} s"
            )
        self.stats.received += 1
        if "error" in answer:
            raise RemoteServiceError(f"service {self.interface}: {answer['error']}")
        try:
            return self.spec.response.load(answer.get("response"))
        except WireError as exc:
            self.stats.errors += 1
            raise RemoteServiceError(f"service {self.interface}: {exc}") from None
