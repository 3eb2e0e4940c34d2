"""Simulated lights and blinds per room: commands in, reported states out, on the bus.

A light switched on or a blind opened also changes the room's luminosity sensor, so the
dashboard and Home Assistant see the effect of a command as they would in a real home.
"""

from __future__ import annotations

from amiro.core import names
from amiro.core.node import Node
from amiro.environment.messages import DEVICE_STATES, DEVICES, DeviceCommand, DeviceState
from amiro.environment.simulated import SimulatedSensorsNode

LUX = {("lights", "on"): 250.0, ("blinds", "open"): 200.0}
BASE_LUX = 50.0


class SimulatedDevicesNode(Node):
    def __init__(
        self, rooms: list[str], home: str = "home", sensors: SimulatedSensorsNode | None = None
    ) -> None:
        super().__init__("devices")
        self.home = home
        self.sensors = sensors
        self.states = {(room, d): DEVICE_STATES[d][1] for room in rooms for d in DEVICES}
        self.rejected = 0

    def on_start(self) -> None:
        self.pub = self.create_publisher(names.DEVICE_STATE, DeviceState)
        self.create_subscription(names.DEVICE_COMMAND, DeviceCommand, self._on_command, 1000)
        for room, device in self.states:
            self._report(room, device)

    def _on_command(self, cmd: DeviceCommand) -> None:
        key = (cmd.room, cmd.device)
        if cmd.home != self.home or key not in self.states:
            self.rejected += 1
            self.log.warning("no %s in room '%s' of home '%s'", cmd.device, cmd.room, cmd.home)
            return
        if cmd.state not in DEVICE_STATES[cmd.device]:
            self.rejected += 1
            self.log.warning("%s cannot be '%s'", cmd.device, cmd.state)
            return
        self.states[key] = cmd.state
        self._report(cmd.room, cmd.device)
        if self.sensors is not None:
            lux = BASE_LUX + sum(LUX.get((d, self.states[(cmd.room, d)]), 0.0) for d in DEVICES)
            self.sensors.set(cmd.room, "luminosity", lux)

    def _report(self, room: str, device: str) -> None:
        state = DeviceState(self.home, room, device, self.states[(room, device)], self.now())
        self.pub.publish(state)
