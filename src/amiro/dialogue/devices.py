"""Device entities made coherent, the way people speak: "ferme les lumières", "închide
lumina" and "shut the lights" switch lights off, "deschide lumina" switches them on; a
state alone names its device ("éteins s'il te plaît": the lights; "lower them": the blinds)."""

from __future__ import annotations

LIGHT_STATES = {"open": "on", "close": "off"}
BLIND_STATES = {"on": "open", "off": "close"}
DEVICE_OF_STATE = {"on": "lights", "off": "lights", "open": "blinds", "close": "blinds"}


def coherent_device(entities: dict[str, str]) -> dict[str, str]:
    """``entities`` of a control_device parse with the state in the device's own terms and
    the device filled in from the state when it was not said."""
    out = dict(entities)
    state = out.get("device_state")
    if state is None:
        return out
    device = out.setdefault("device_entity", DEVICE_OF_STATE[state])
    table = LIGHT_STATES if device == "lights" else BLIND_STATES
    out["device_state"] = table.get(state, state)
    return out
