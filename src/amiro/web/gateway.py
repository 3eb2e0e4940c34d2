"""The gateway between the web server's thread and the single-threaded runtime.

On the runtime's thread, :class:`GatewayNode` keeps a JSON-ready snapshot of what the
dashboard shows (robot, path, people, behaviours, transcript, sensors, devices) and runs
the jobs the web posts.  The web thread only reads the last snapshot (an atomic reference
swap) and posts jobs whose results come back through futures.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable
from concurrent.futures import Future
from typing import Any, TypeVar

import numpy as np

from amiro.core import names
from amiro.core.inbox import Inbox
from amiro.core.messages import (
    Acknowledgement,
    BehaviorEvent,
    LaserScan,
    Path,
    SensorReading,
    SpeechHeard,
    SpeechRequest,
    String,
)
from amiro.core.node import Node
from amiro.core.safety import estop_engaged
from amiro.environment.devices import SimulatedDevicesNode
from amiro.environment.messages import DeviceState
from amiro.web.robot import RobotPort

T = TypeVar("T")
EVENTS_SHOWN = 120  # the timeline's length: a whole hydration run is about 25 events


class GatewayNode(Node):
    def __init__(
        self,
        robot: RobotPort,
        devices: SimulatedDevicesNode | None = None,
        period_s: float = 0.1,
        history: int = 300,
    ) -> None:
        super().__init__("web_gateway")
        self.robot = robot
        self.devices_node = devices
        self.period_s = period_s
        self.inbox = Inbox()
        self.snapshot: dict[str, Any] = {}
        self.transcript: deque[dict[str, Any]] = deque(maxlen=history)
        self.events: deque[dict[str, Any]] = deque(maxlen=history)
        self.acks: deque[dict[str, Any]] = deque(maxlen=history)
        self.sensors: dict[str, dict[str, float]] = {}
        self.devices: dict[str, dict[str, str]] = {}
        self.path: list[tuple[float, float]] = []
        self.scan: LaserScan | None = None
        self.estop = False

    def on_start(self) -> None:
        self.create_subscription(names.SAY, SpeechRequest, self._on_say, 100)
        self.create_subscription(names.HEARD, SpeechHeard, self._on_heard, 100)
        self.create_subscription(names.PATH, Path, self._on_path, 10)
        self.create_subscription(names.EVENTS, BehaviorEvent, self._on_event, 1000)
        self.create_subscription(names.ACK, Acknowledgement, self._on_ack, 1000)
        self.create_subscription(names.SENSORS, SensorReading, self._on_reading, 1000)
        self.create_subscription(names.DEVICE_STATE, DeviceState, self._on_device, 1000)
        self.create_subscription(names.SCAN, LaserScan, self._on_scan, 1)
        self.create_subscription(names.EMERGENCY_STOP, String, self._on_estop, 10)
        self.create_timer(self.period_s, self._tick)
        if self.devices_node is not None:  # their first reports went out before this started
            for (room, device), state in self.devices_node.states.items():
                self._note_device(room, device, state)
        self._tick()

    # --- any thread -------------------------------------------------------------------------
    def call(self, job: Callable[[], T]) -> Future[T]:
        """Run ``job`` on the runtime's thread; its result (or exception) comes in the future."""
        future: Future[T] = Future()

        def run() -> None:
            if not future.set_running_or_notify_cancel():
                return
            try:
                future.set_result(job())
            except Exception as exc:
                future.set_exception(exc)

        self.inbox.post(run)
        return future

    # --- runtime thread ---------------------------------------------------------------------
    def note_chat(self, who: str, text: str, lang: str) -> None:
        self.transcript.append({"t": round(self.now(), 2), "who": who, "text": text, "lang": lang})

    def _on_say(self, msg: SpeechRequest) -> None:
        self.note_chat("robot", msg.text, msg.lang)

    def _on_heard(self, msg: SpeechHeard) -> None:
        self.note_chat(msg.speaker or "someone", msg.text, msg.lang)

    def _on_path(self, msg: Path) -> None:
        self.path = [(round(p.x, 2), round(p.y, 2)) for p in msg.poses]

    def _on_event(self, ev: BehaviorEvent) -> None:
        self.events.append(ev.to_dict())

    def _on_ack(self, ack: Acknowledgement) -> None:
        self.acks.append({"id": ack.id, "status": ack.status, "ts": ack.ts})

    def _on_scan(self, scan: LaserScan) -> None:
        self.scan = scan

    def _on_estop(self, msg: String) -> None:
        self.estop = estop_engaged(msg.data)

    def scan_points(self, most: int = 360) -> list[tuple[float, float]]:
        """The last lidar scan's hits in the map frame, at most ``most`` of them (the laser
        is at the base's centre; the pose is the robot's as the dashboard shows it)."""
        pose, scan = self.robot.state().get("robot"), self.scan
        if scan is None or pose is None:
            return []
        ranges = np.asarray(scan.ranges, dtype=np.float64)
        angles = scan.angles() + pose["theta"]
        hit = np.isfinite(ranges) & (ranges >= scan.range_min) & (ranges < scan.range_max)
        step = max(1, int(np.ceil(hit.sum() / most)))
        r, a = ranges[hit][::step], angles[hit][::step]
        xs, ys = pose["x"] + r * np.cos(a), pose["y"] + r * np.sin(a)
        return [(round(float(x), 2), round(float(y), 2)) for x, y in zip(xs, ys, strict=True)]

    def _on_reading(self, r: SensorReading) -> None:
        self.sensors.setdefault(r.room, {})[r.sensor] = round(r.value, 2)

    def _on_device(self, s: DeviceState) -> None:
        self._note_device(s.room, s.device, s.state)

    def _note_device(self, room: str, device: str, state: str) -> None:
        self.devices.setdefault(room, {})[device] = state

    def _tick(self) -> None:
        self.inbox.drain()
        self.snapshot = self._build()

    def _build(self) -> dict[str, Any]:
        return {
            "t": round(self.now(), 2),
            "clock": self.runtime.clock.iso(self.now()),
            **self.robot.state(),
            "path": self.path,
            "transcript": list(self.transcript)[-30:],
            "events": list(self.events)[-EVENTS_SHOWN:],
            "estop": self.estop,
            "acks": list(self.acks)[-20:],
            "sensors": {room: dict(values) for room, values in self.sensors.items()},
            "devices": {room: dict(states) for room, states in self.devices.items()},
        }
