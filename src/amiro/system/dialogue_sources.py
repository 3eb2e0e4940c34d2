"""The dialogue's answer sources backed by the smart environment (``build_system`` uses it;
standalone ``amiro chat`` keeps the offline fixtures)."""

from __future__ import annotations

from amiro.core import names
from amiro.core.runtime import Runtime
from amiro.dialogue.sources import OfflineWeather, Sources
from amiro.environment.assembly import Environment
from amiro.environment.days import clock_date
from amiro.environment.dialogue_calendar import ConfiguredCalendar
from amiro.environment.dialogue_devices import BusDeviceControl
from amiro.environment.dialogue_health import StoreHealth
from amiro.environment.messages import DeviceCommand


def environment_sources(runtime: Runtime, environment: Environment, rooms: list[str]) -> Sources:
    """Health from the store, the agenda from the reminders config, devices over the bus;
    the weather stays offline (amiro fetches nothing from the internet)."""
    clock, cfg = runtime.clock, environment.config
    commands = runtime.bus.publisher(names.DEVICE_COMMAND, DeviceCommand)
    return Sources(
        health=StoreHealth(environment.health, lambda: clock_date(clock), cfg.health_rules),
        calendar=ConfiguredCalendar(cfg.reminders, clock),
        weather=OfflineWeather(),
        devices=BusDeviceControl(commands, cfg.home_id, rooms),
    )
