"""The MQTT bridge (paho-mqtt 2.x): the contract's topics in, bus messages out, and back.

paho runs its network loop in its own thread; inbound messages are posted to an
:class:`Inbox` and decoded on the runtime's thread, so counters and the bus stay
single-threaded.  Subscriptions use MQTT 5's no-local option: the robot's own sensor
readings and device states, published for Home Assistant, never come back as input.
"""

from __future__ import annotations

import json
from collections import Counter
from functools import partial
from typing import Any
from urllib.parse import urlsplit

import paho.mqtt.client as mqtt
from paho.mqtt.enums import CallbackAPIVersion
from paho.mqtt.subscribeoptions import SubscribeOptions
from pydantic import Field

from amiro.core import names
from amiro.core.bus import Publisher
from amiro.core.config import ConfigError, Section
from amiro.core.inbox import Inbox
from amiro.core.messages import Acknowledgement, BehaviorEvent, Notification, SensorReading
from amiro.core.node import Node
from amiro.environment.discovery import availability_topic, discovery_messages, status_topic
from amiro.environment.messages import DeviceCommand, DeviceState, HealthMeasurement
from amiro.environment.payloads import (
    PayloadError,
    decode,
    device_topic,
    encode_ack,
    encode_reading,
    encode_state,
    sensor_topic,
)


class MqttConfig(Section):
    url: str = Field(description="mqtt://HOST:PORT")
    client_id: str = "amiro"
    username: str | None = None
    password: str | None = None
    qos: int = Field(default=1, ge=0, le=2)
    discovery: bool = True
    discovery_prefix: str = "homeassistant"
    keepalive_s: int = Field(default=30, ge=5)
    poll_s: float = Field(default=0.05, gt=0.0, description="how often inbound messages are read")


def parse_url(url: str) -> tuple[str, int]:
    """``mqtt://host:port`` → (host, port); a one-line ConfigError otherwise."""
    parts = urlsplit(url)
    if parts.scheme != "mqtt" or not parts.hostname:
        raise ConfigError(f"MQTT broker '{url}': expected mqtt://HOST[:PORT]")
    try:
        port = parts.port or 1883
    except ValueError:
        raise ConfigError(f"MQTT broker '{url}': bad port") from None
    return parts.hostname, port


class MqttBridgeNode(Node):
    def __init__(self, config: MqttConfig, home: str, rooms: list[str]) -> None:
        super().__init__("mqtt_bridge")
        self.config = config
        self.home = home
        self.rooms = rooms
        self.host, self.port = parse_url(config.url)
        self.inbox = Inbox()
        self.counts: Counter[str] = Counter()
        self.last_error = ""
        self.connected = False
        self._unreachable = False  # paho thread: the outage was already reported
        self._client: mqtt.Client | None = None

    # --- lifecycle ------------------------------------------------------------------------
    def on_start(self) -> None:
        self.pubs: dict[str, Publisher[Any]] = {
            "sensor": self.create_publisher(names.SENSORS, SensorReading),
            "health": self.create_publisher(names.HEALTH, HealthMeasurement),
            "notification": self.create_publisher(names.NOTIFICATIONS, Notification),
            "command": self.create_publisher(names.DEVICE_COMMAND, DeviceCommand),
        }
        self.create_subscription(names.SENSORS, SensorReading, self._export_reading, 1000)
        self.create_subscription(names.DEVICE_STATE, DeviceState, self._export_state, 1000)
        self.create_subscription(names.ACK, Acknowledgement, self._export_ack, 10_000)
        self.create_subscription(names.EVENTS, BehaviorEvent, self._export_status, 1000)
        self.create_timer(self.config.poll_s, self._drain)
        self._injected: set[int] = set()
        self._client = self._connect()

    def on_stop(self) -> None:
        client, self._client = self._client, None
        if client is not None:
            client.publish(availability_topic(self.home), b"offline", qos=1, retain=True)
            client.disconnect()
            client.loop_stop()
        self.connected = False

    def _connect(self) -> mqtt.Client:
        client = mqtt.Client(
            callback_api_version=CallbackAPIVersion.VERSION2,
            client_id=self.config.client_id,
            protocol=mqtt.MQTTv5,
        )
        if self.config.username is not None:
            client.username_pw_set(self.config.username, self.config.password)
        client.will_set(availability_topic(self.home), b"offline", qos=1, retain=True)
        client.on_connect = self._on_connect
        client.on_connect_fail = self._on_connect_fail
        client.on_disconnect = self._on_disconnect
        client.on_message = self._on_message
        client.reconnect_delay_set(min_delay=1, max_delay=30)
        client.connect_async(self.host, self.port, keepalive=self.config.keepalive_s)
        client.loop_start()
        return client

    def _drain(self) -> None:
        self.inbox.drain()

    # --- paho thread ----------------------------------------------------------------------
    def _on_connect(self, client: mqtt.Client, _u: Any, _f: Any, rc: Any, _p: Any) -> None:
        if rc.is_failure:
            self.inbox.post(partial(self._note_error, f"connection refused: {rc}"))
            return
        options = SubscribeOptions(qos=self.config.qos, noLocal=True)
        client.subscribe([(f"amiro/{self.home}/#", options)])
        client.publish(availability_topic(self.home), b"online", qos=1, retain=True)
        if self.config.discovery:
            for topic, payload in discovery_messages(
                self.home, self.rooms, self.config.discovery_prefix
            ):
                client.publish(topic, payload, qos=1, retain=True)
        self.connected = True
        self._unreachable = False

    def _on_connect_fail(self, _c: mqtt.Client, _u: Any) -> None:
        """The broker cannot be reached (a wrong host or port, or it is down): said once,
        not at every retry, since paho keeps retrying."""
        if not self._unreachable:
            self._unreachable = True
            where = f"{self.host}:{self.port}"
            self.inbox.post(partial(self._note_error, f"broker {where} unreachable; retrying"))

    def _on_disconnect(self, _c: mqtt.Client, _u: Any, _f: Any, rc: Any, _p: Any) -> None:
        self.connected = False

    def _on_message(self, _c: mqtt.Client, _u: Any, msg: mqtt.MQTTMessage) -> None:
        self.inbox.post(partial(self._handle, msg.topic, bytes(msg.payload)))

    # --- runtime thread -------------------------------------------------------------------
    def _note_error(self, text: str) -> None:
        self.last_error = text
        self.log.error("MQTT %s", text)

    def _handle(self, topic: str, payload: bytes) -> None:
        """Decode one inbound message; a malformed one is logged and counted, never fatal."""
        self.counts["received"] += 1
        if topic.endswith(("/state", "/notifications/ack", "/robot/status", "/availability")):
            self.counts["ignored"] += 1  # outputs of this or another robot, not inputs
            return
        now = self.now()
        try:
            decoded = decode(topic, payload, self.home, now, self.runtime.clock.iso(now))
        except PayloadError as exc:
            self.counts["malformed"] += 1
            self.last_error = f"{topic[:80]}: {exc}"
            self.log.info("malformed MQTT message on %s: %s", topic[:80], exc)
            return
        self.counts[decoded.kind] += 1
        if decoded.kind == "sensor":
            self._injected.add(id(decoded.message))
        self.pubs[decoded.kind].publish(decoded.message)

    def _publish(self, topic: str, payload: bytes, retain: bool = False) -> None:
        if self._client is not None:
            self._client.publish(topic, payload, qos=self.config.qos, retain=retain)
            self.counts["published"] += 1

    def _export_reading(self, reading: SensorReading) -> None:
        if id(reading) in self._injected:  # came from MQTT: do not echo it back
            self._injected.discard(id(reading))
            return
        if reading.home == self.home:
            self._publish(
                sensor_topic(self.home, reading.room, reading.sensor), encode_reading(reading)
            )

    def _export_state(self, state: DeviceState) -> None:
        topic = device_topic(self.home, state.room, state.device, "state")
        self._publish(topic, encode_state(state), retain=True)

    def _export_ack(self, ack: Acknowledgement) -> None:
        self._publish(f"amiro/{self.home}/notifications/ack", encode_ack(ack))

    def _export_status(self, ev: BehaviorEvent) -> None:
        if ev.type == "task_started":
            activity = f"{ev.graph}: {ev.detail.get('task_type', ev.task)}"
        elif ev.type == "graph_finished":
            activity = "idle"
        else:
            return
        self._publish(status_topic(self.home), json.dumps({"activity": activity}).encode(), True)
