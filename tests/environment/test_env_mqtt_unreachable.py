"""A broker that cannot be reached (a mistyped host or port, or one that is down): the bridge
says so once, on the log and in ``last_error``, and keeps retrying."""

from __future__ import annotations

import logging
import socket
import time

import pytest

from amiro.core.clock import SimClock
from amiro.core.runtime import Runtime
from amiro.environment.mqtt_bridge import MqttBridgeNode, MqttConfig


def test_an_unreachable_broker_is_reported_once(caplog: pytest.LogCaptureFixture) -> None:
    with socket.socket() as sock:  # a port nobody listens on
        sock.bind(("127.0.0.1", 0))
        port = sock.getsockname()[1]
    rt = Runtime(SimClock())
    config = MqttConfig(url=f"mqtt://127.0.0.1:{port}", client_id="amiro-unreachable")
    bridge = rt.add(MqttBridgeNode(config, "home", ["kitchen"]))
    with caplog.at_level(logging.ERROR):
        rt.start()
        deadline = time.monotonic() + 10
        while "unreachable" not in bridge.last_error and time.monotonic() < deadline:
            rt.spin_for(0.1)
        time.sleep(2.5)  # paho retries after 1 s, then 2 s: no second report
        rt.spin_for(0.2)
        rt.stop()
    assert bridge.last_error == f"broker 127.0.0.1:{port} unreachable; retrying"
    assert not bridge.connected
    reports = [r for r in caplog.records if "unreachable" in r.getMessage()]
    assert len(reports) == 1
