"""A real mosquitto broker on a free loopback port (fixtures) and a test-side MQTT peer."""

from __future__ import annotations

import json
import shutil
import socket
import subprocess
import threading
import time
from collections.abc import Callable, Iterator
from pathlib import Path

import paho.mqtt.client as mqtt
import pytest
from paho.mqtt.enums import CallbackAPIVersion

MOSQUITTO = shutil.which("mosquitto") or "/usr/sbin/mosquitto"


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@pytest.fixture
def broker(tmp_path: Path) -> Iterator[str]:
    port = free_port()
    conf = tmp_path / "mosquitto.conf"
    conf.write_text(f"listener {port} 127.0.0.1\nallow_anonymous true\npersistence false\n")
    proc = subprocess.Popen(
        [MOSQUITTO, "-c", str(conf)], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
    )
    deadline = time.monotonic() + 10
    while True:
        try:
            socket.create_connection(("127.0.0.1", port), timeout=0.2).close()
            break
        except OSError:
            if time.monotonic() > deadline or proc.poll() is not None:
                proc.kill()
                raise RuntimeError("mosquitto did not start") from None
            time.sleep(0.05)
    yield f"mqtt://127.0.0.1:{port}"
    proc.terminate()
    proc.wait(timeout=10)


class Peer:
    """A test-side MQTT client: publishes and records what arrives on its subscriptions."""

    def __init__(self, url: str, topics: list[str]) -> None:
        host, port = url.removeprefix("mqtt://").split(":")
        self.messages: list[tuple[str, bytes]] = []
        self.lock = threading.Lock()
        self.ready = threading.Event()
        self.client = mqtt.Client(callback_api_version=CallbackAPIVersion.VERSION2)
        self.client.on_message = self._on_message
        self.client.on_connect = lambda c, *_: (
            c.subscribe([(t, 1) for t in topics]) if topics else None,
            self.ready.set(),
        )
        self.client.connect(host, int(port))
        self.client.loop_start()
        assert self.ready.wait(5), "test client could not connect"
        time.sleep(0.2)  # let the SUBACK arrive

    def _on_message(self, _c: mqtt.Client, _u: object, msg: mqtt.MQTTMessage) -> None:
        with self.lock:
            self.messages.append((msg.topic, bytes(msg.payload)))

    def publish(self, topic: str, payload: bytes | str | dict[str, object], qos: int = 1) -> None:
        if isinstance(payload, dict):
            payload = json.dumps(payload)
        self.client.publish(topic, payload, qos=qos).wait_for_publish(5)

    def received(self, topic_filter: Callable[[str], bool]) -> list[tuple[str, bytes]]:
        with self.lock:
            return [m for m in self.messages if topic_filter(m[0])]

    def close(self) -> None:
        self.client.disconnect()
        self.client.loop_stop()


@pytest.fixture
def peer_factory(broker: str) -> Iterator[Callable[[list[str]], Peer]]:
    peers: list[Peer] = []

    def make(topics: list[str]) -> Peer:
        peer = Peer(broker, topics)
        peers.append(peer)
        return peer

    yield make
    for p in peers:
        p.close()


def wait_for(predicate: Callable[[], bool], timeout: float, step: Callable[[], None]) -> bool:
    """Run ``step`` (e.g. spin the runtime a little) until ``predicate`` holds or time is up."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        step()
        if predicate():
            return True
        time.sleep(0.005)
    return predicate()
