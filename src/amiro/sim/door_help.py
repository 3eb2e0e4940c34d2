"""A resident asked to open a door does so: the closed door nearest to them opens.

The robot asks with a Say whose act is :data:`OPEN_DOOR_REQUEST` (the key of the request in
``phrases.yaml``, whatever the language); a resident whose script confirms walks over and
opens it :data:`DOOR_OPENING_S` after answering.
"""

from __future__ import annotations

import math

from amiro.home.world import World
from amiro.sim.residents import Resident

OPEN_DOOR_REQUEST = "open_door_request"  # the dialogue act, as the planner's dispatch sends it
DOOR_OPENING_S = 4.0


def open_nearest_door(world: World, resident: Resident) -> str | None:
    """Open the closed door nearest to ``resident``; returns its name (None: all open)."""
    closed = [d for d in world.home.doors if not world.doors[d.name]]
    if not closed:
        return None
    door = min(
        closed,
        key=lambda d: math.hypot(
            0.5 * (d.a[0] + d.b[0]) - resident.x, 0.5 * (d.a[1] + d.b[1]) - resident.y
        ),
    )
    world.set_door(door.name, True)
    return door.name
