"""MCAP files with ROS 2 schemas: written from the bus, read back as bus messages.

Messages are converted by the bridge's codecs and serialised to CDR by rosbags' pure-Python
typestore, so recording needs no ROS install and the file opens in Foxglove (``ros2msg``
schemas, ``cdr`` encoding) and in ``ros2 bag``'s MCAP storage.  Times are clock seconds.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import Any, BinaryIO

from mcap.exceptions import McapError
from mcap.reader import make_reader
from mcap.writer import Writer

from amiro.core.config import ConfigError
from amiro.core.node import Node
from amiro.ros2.routes import ROUTES, Route, route
from amiro.ros2.types import RosbagsTypes

PROFILE = "ros2"
NS = 1_000_000_000


def _ns(t: float) -> int:
    return max(0, round(t * NS))


class McapRecorder(Node):
    """Writes bus topics to an MCAP file until stopped.

    By default it records every routed topic already on the bus with the route's type, so
    add it to the runtime after the nodes whose traffic it should keep.
    """

    def __init__(self, path: Path, topics: list[str] | None = None) -> None:
        super().__init__("mcap_recorder")
        self.path = path
        self.types = RosbagsTypes()
        self.routes = [route(t) for t in topics] if topics is not None else None
        self.counts: dict[str, int] = {}
        self._file: BinaryIO | None = None
        self._writer: Writer | None = None
        self._channels: dict[str, int] = {}

    def on_start(self) -> None:
        try:
            self._file = self.path.open("wb")
        except OSError as exc:
            raise ConfigError(f"{self.path}: cannot write: {exc.strerror}") from None
        self._writer = Writer(self._file)
        self._writer.start(profile=PROFILE, library="amiro")
        schemas: dict[str, int] = {}
        for r in self.routes if self.routes is not None else self._routes_on_bus():
            type_name = r.codec.ros_type
            if type_name not in schemas:
                text, _ = self.types.store.generate_msgdef(type_name)
                schemas[type_name] = self._writer.register_schema(
                    type_name, "ros2msg", text.encode()
                )
            self._channels[r.topic] = self._writer.register_channel(
                r.topic, "cdr", schemas[type_name]
            )
            self.create_subscription(r.topic, r.codec.bus_type, partial(self._write, r), depth=1000)

    def _routes_on_bus(self) -> list[Route]:
        on_bus = self.runtime.bus.topics()
        return [r for t, r in ROUTES.items() if on_bus.get(t) == r.codec.bus_type.__name__]

    def _write(self, r: Route, msg: Any) -> None:
        assert self._writer is not None
        now = self.now()
        data = self.types.store.serialize_cdr(
            r.codec.encode(self.types, msg, now), r.codec.ros_type
        )
        seq = self.counts.get(r.topic, 0)
        self._writer.add_message(self._channels[r.topic], _ns(now), bytes(data), _ns(now), seq)
        self.counts[r.topic] = seq + 1

    def on_stop(self) -> None:
        if self._writer is not None:
            self._writer.finish()  # type: ignore[no-untyped-call]
            self._writer = None
        if self._file is not None:
            self._file.close()
            self._file = None


@dataclass(frozen=True)
class Recorded:
    topic: str
    t: float
    msg: Any


def read_mcap(path: Path, skipped: dict[str, int] | None = None) -> Iterator[Recorded]:
    """Bus messages of an MCAP file in time order; topics amiro has no route for are counted
    in ``skipped`` and left out."""
    types = RosbagsTypes()
    if not path.is_file():
        raise ConfigError(f"{path}: no such file")
    with path.open("rb") as f:
        try:
            for schema, channel, message in make_reader(f).iter_messages():
                r = ROUTES.get(channel.topic)
                if r is None or schema is None or schema.name != r.codec.ros_type:
                    if skipped is not None:
                        skipped[channel.topic] = skipped.get(channel.topic, 0) + 1
                    continue
                ros = types.store.deserialize_cdr(message.data, schema.name)
                yield Recorded(channel.topic, message.log_time / NS, r.codec.decode(ros))
        except (McapError, ValueError, KeyError, EOFError) as exc:
            raise ConfigError(f"{path}: not a readable MCAP file: {exc}") from None


class McapReplayer(Node):
    """Publishes a recording's messages on the bus at their recorded times (clock time)."""

    def __init__(self, path: Path) -> None:
        super().__init__("mcap_replayer")
        self.path = path
        self.skipped: dict[str, int] = {}
        self.counts: dict[str, int] = {}
        self.finished = False

    def on_start(self) -> None:
        self._messages = read_mcap(self.path, self.skipped)
        self._offset: float | None = None
        self._publish_due()

    def _publish_due(self) -> None:
        for rec in self._messages:
            if self._offset is None:
                self._offset = self.now() - rec.t
            due = rec.t + self._offset
            if due > self.now():
                self.call_later(due - self.now(), partial(self._send_then_continue, rec))
                return
            self._send(rec)
        self.finished = True

    def _send(self, rec: Recorded) -> None:
        self.runtime.bus.publish(rec.topic, rec.msg)
        self.counts[rec.topic] = self.counts.get(rec.topic, 0) + 1

    def _send_then_continue(self, rec: Recorded) -> None:
        self._send(rec)
        self._publish_due()
