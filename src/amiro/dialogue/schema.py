"""The NLU label schema of CONTRACTS.md section 2: intents and the entities each may carry."""

from __future__ import annotations

INTENT_ENTITIES: dict[str, tuple[str, ...]] = {
    "get_health": ("health_entity", "output_entity", "dateandtime_entity"),
    "get_info": ("info_entity",),
    "get_weather": ("dateandtime_entity", "location_entity"),
    "get_calendar": ("dateandtime_entity", "output_entity"),
    "control_device": ("device_entity", "device_state", "room_entity"),
    "go_to": ("person_entity", "room_entity"),
    "affirm": (),
    "deny": (),
    "postpone": ("duration",),
    "greet": (),
    "goodbye": (),
    "out_of_scope": (),
}
OUT_OF_SCOPE = "out_of_scope"
