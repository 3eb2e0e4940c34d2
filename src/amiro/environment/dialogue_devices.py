"""Spoken device commands onto the bus (the dialogue's ``DeviceControl``).

They take the path every device command takes (dashboard, MQTT ``.../set``): a
``DeviceCommand`` on the bus, which the simulated devices node (or a real home's bridge)
carries out and reports back as a ``DeviceState``.
"""

from __future__ import annotations

from collections.abc import Iterable

from amiro.core.bus import Publisher
from amiro.environment.messages import DEVICE_STATES, DeviceCommand


class BusDeviceControl:
    def __init__(self, commands: Publisher[DeviceCommand], home: str, rooms: Iterable[str]) -> None:
        self.commands = commands
        self.home = home
        self.rooms = frozenset(rooms)

    def set(self, room: str, device: str, state: str) -> bool:
        """Sends the command; False when the home has no such room, device or state."""
        if room not in self.rooms or state not in DEVICE_STATES.get(device, ()):
            return False
        self.commands.publish(DeviceCommand(self.home, room, device, state))
        return True
