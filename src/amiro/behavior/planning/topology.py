"""The home as the planner sees it: rooms, waypoints and the doors between them.

Planning does not need the occupancy grid, only where the robot can stop (one waypoint per
room and one on each side of every door) and which waypoints a door links.  The topology is
read from a :class:`~amiro.home.world.World` or generated (for benchmarks), and it is all a
PDDL problem's static facts are made of.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from amiro.core.config import ConfigError
from amiro.home.world import World

DOOR_OFFSETS_M = (0.6, 0.5, 0.75, 0.45, 0.9)  # tried in order: distance from the door line
ROBOT_CLEARANCE_M = 0.38  # robot radius and the costmap safety margin


@dataclass(frozen=True, slots=True)
class Waypoint:
    name: str
    room: str
    x: float
    y: float
    door: str | None = None  # the door this waypoint stands before, if any


@dataclass(frozen=True, slots=True)
class Doorway:
    """A door and its two waypoints, ``sides[i]`` in ``rooms[i]``."""

    name: str
    rooms: tuple[str, str]
    sides: tuple[str, str]
    a: tuple[float, float]
    b: tuple[float, float]

    @property
    def centre(self) -> tuple[float, float]:
        return (0.5 * (self.a[0] + self.b[0]), 0.5 * (self.a[1] + self.b[1]))


@dataclass
class Topology:
    """Rooms, waypoints and doors of one home."""

    name: str
    rooms: tuple[str, ...]
    waypoints: dict[str, Waypoint]
    doors: dict[str, Doorway]
    _by_room: dict[str, list[str]] = field(default_factory=dict, repr=False)

    def __post_init__(self) -> None:
        for wp in self.waypoints.values():
            self._by_room.setdefault(wp.room, []).append(wp.name)

    def in_room(self, room: str) -> list[str]:
        return list(self._by_room.get(room, []))

    def distance(self, a: str, b: str) -> float:
        p, q = self.waypoints[a], self.waypoints[b]
        return math.hypot(p.x - q.x, p.y - q.y)

    def nearest(self, x: float, y: float, room: str) -> str:
        names = self.in_room(room)
        if not names:
            raise ConfigError(f"room {room} has no waypoint")
        return min(
            names, key=lambda n: math.hypot(self.waypoints[n].x - x, self.waypoints[n].y - y)
        )


def topology_from_world(world: World) -> Topology:
    """One waypoint per room (its place of the same name, else its centroid) and one on each
    side of every door, far enough from the frame for the robot to stand."""
    rooms = tuple(world.room_names())
    waypoints: dict[str, Waypoint] = {}
    for room in rooms:
        if room in world.home.places:
            p = world.place(room)
            x, y = p.x, p.y
        else:
            x, y = (float(v) for v in world.room_polygon(room).mean(axis=0))
        waypoints[f"{room}_centre"] = Waypoint(f"{room}_centre", room, x, y)
    doors: dict[str, Doorway] = {}
    for spec in world.home.doors:
        sides = tuple(_door_side(world, spec.name, spec.a, spec.b, r) for r in spec.rooms)
        for room, (x, y) in zip(spec.rooms, sides, strict=True):
            name = f"{spec.name}_{room}"
            waypoints[name] = Waypoint(name, room, x, y, spec.name)
        doors[spec.name] = Doorway(
            spec.name,
            spec.rooms,
            (f"{spec.name}_{spec.rooms[0]}", f"{spec.name}_{spec.rooms[1]}"),
            spec.a,
            spec.b,
        )
    return Topology(world.name, rooms, waypoints, doors)


def _door_side(
    world: World, door: str, a: tuple[float, float], b: tuple[float, float], room: str
) -> tuple[float, float]:
    mx, my = 0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])
    length = math.hypot(b[0] - a[0], b[1] - a[1])
    nx, ny = -(b[1] - a[1]) / length, (b[0] - a[0]) / length
    for offset in DOOR_OFFSETS_M:
        for sign in (1.0, -1.0):
            x, y = mx + sign * offset * nx, my + sign * offset * ny
            if world.room_at(x, y) == room and world.is_free(x, y, ROBOT_CLEARANCE_M):
                return x, y
    raise ConfigError(f"door {door}: no free spot for the robot on the {room} side")


def grid_topology(n_rooms: int, rng: np.random.Generator, extra_doors: float = 0.3) -> Topology:
    """A generated home of ``n_rooms`` 4 m square rooms on a grid: a random spanning tree of
    doors, so every room is reachable, plus a share of extra doors that make loops."""
    if n_rooms < 1:
        raise ConfigError(f"a home needs at least one room, got {n_rooms}")
    cols = math.ceil(math.sqrt(n_rooms))
    cells = {i: (i % cols, i // cols) for i in range(n_rooms)}
    pairs = [
        (i, j)
        for i in cells
        for j in cells
        if i < j and abs(cells[i][0] - cells[j][0]) + abs(cells[i][1] - cells[j][1]) == 1
    ]
    order = rng.permutation(len(pairs))
    parent = list(range(n_rooms))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    chosen: list[tuple[int, int]] = []
    spare: list[tuple[int, int]] = []
    for k in order:
        i, j = pairs[int(k)]
        if root(i) != root(j):
            parent[root(i)] = root(j)
            chosen.append((i, j))
        else:
            spare.append((i, j))
    chosen += spare[: round(extra_doors * len(spare))]
    size = 4.0
    rooms = tuple(f"room{i}" for i in range(n_rooms))
    waypoints = {
        f"{r}_centre": Waypoint(
            f"{r}_centre", r, (cells[i][0] + 0.5) * size, (cells[i][1] + 0.5) * size
        )
        for i, r in enumerate(rooms)
    }
    doors: dict[str, Doorway] = {}
    for i, j in chosen:
        name = f"door{i}_{j}"
        (ci, ri), (cj, rj) = cells[i], cells[j]
        mx, my = (
            (max(ci, cj) * size, (ri + 0.5) * size)
            if ri == rj
            else ((ci + 0.5) * size, max(ri, rj) * size)
        )
        dx, dy = (cj - ci, rj - ri)
        for room, sign in ((rooms[i], -1.0), (rooms[j], 1.0)):
            wp = f"{name}_{room}"
            waypoints[wp] = Waypoint(wp, room, mx + sign * 0.6 * dx, my + sign * 0.6 * dy, name)
        half = 0.45
        a = (mx - half * abs(dy), my - half * abs(dx))
        b = (mx + half * abs(dy), my + half * abs(dx))
        doors[name] = Doorway(
            name, (rooms[i], rooms[j]), (f"{name}_{rooms[i]}", f"{name}_{rooms[j]}"), a, b
        )
    return Topology(f"grid{n_rooms}", rooms, waypoints, doors)
