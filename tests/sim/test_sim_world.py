"""The default apartment and the World queries built on it."""

from __future__ import annotations

from collections import deque
from pathlib import Path

import numpy as np
import pytest
from scipy import ndimage

from amiro.core.config import ConfigError
from amiro.core.gridmap import load_map
from amiro.home.world import World, default_home_path, render_home

ROOMS = {"hallway", "living_room", "kitchen", "bedroom", "bathroom"}
ROBOT_RADIUS = 0.25


@pytest.fixture(scope="module")
def world() -> World:
    return World.load(default_home_path())


def reachable(world: World, start: tuple[float, float]) -> np.ndarray:
    """BFS over the rendered map inflated by the robot radius."""
    grid = world.render()
    occ = grid.data != 0
    r = int(np.ceil(ROBOT_RADIUS / grid.resolution))
    yy, xx = np.mgrid[-r : r + 1, -r : r + 1]
    inflated = ndimage.binary_dilation(occ, structure=(xx * xx + yy * yy) <= r * r)
    c, rr = grid.world_to_cell(*start)
    seen = np.zeros_like(occ)
    q = deque([(int(rr), int(c))])
    seen[int(rr), int(c)] = True
    while q:
        y, x = q.popleft()
        for dy, dx in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            ny, nx = y + dy, x + dx
            if (
                0 <= ny < occ.shape[0]
                and 0 <= nx < occ.shape[1]
                and not seen[ny, nx]
                and not inflated[ny, nx]
            ):
                seen[ny, nx] = True
                q.append((ny, nx))
    return np.asarray(seen, dtype=bool)


def is_reached(world: World, seen: np.ndarray, name: str) -> bool:
    p = world.place(name)
    c, r = world.render().world_to_cell(p.x, p.y)
    return bool(seen[int(r), int(c)])


def test_rooms_and_room_at(world: World) -> None:
    assert set(world.home.rooms) == ROOMS
    assert world.room_at(0.8, 1.0) == "hallway"
    assert world.room_at(8.0, 2.0) == "living_room"
    assert world.room_at(8.0, 6.5) == "kitchen"
    assert world.room_at(1.0, 7.0) == "bedroom"
    assert world.room_at(5.0, 6.0) == "bathroom"
    assert world.room_at(-1.0, -1.0) is None


def test_places_inside_rooms_and_free(world: World) -> None:
    expected = {
        "dock": "hallway",
        "couch": "living_room",
        "desk": "living_room",
        "bed": "bedroom",
        "kitchen_table": "kitchen",
        "bathroom": "bathroom",
    }
    for name, room in expected.items():
        p = world.place(name)
        assert world.room_at(p.x, p.y) == room, name
    for name in world.home.places:
        p = world.place(name)
        assert world.is_free(p.x, p.y, ROBOT_RADIUS), name
    with pytest.raises(KeyError):
        world.place("attic")


def test_every_room_reachable_from_dock() -> None:
    world = World.load(default_home_path())
    seen = reachable(world, (world.place("dock").x, world.place("dock").y))
    for place in world.home.places:
        assert is_reached(world, seen, place), place


def test_closed_door_isolates_and_reroutes() -> None:
    world = World.load(default_home_path())
    dock = world.place("dock")
    world.set_door("bedroom_door", False)
    seen = reachable(world, (dock.x, dock.y))
    assert not is_reached(world, seen, "bed")
    assert is_reached(world, seen, "couch")
    world.set_door("bedroom_door", True)
    world.set_door("living_door", False)  # the living room is still reachable via the kitchen
    seen = reachable(world, (dock.x, dock.y))
    assert is_reached(world, seen, "couch") and is_reached(world, seen, "bed")


def test_doors_and_obstacles_change_live_occupancy() -> None:
    world = World.load(default_home_path())
    assert world.is_free(1.45, 5.0, 0.2)  # in the open bedroom doorway
    v = world.version
    world.set_door("bedroom_door", False)
    assert world.version > v
    assert not world.is_free(1.45, 5.0, 0.2)
    assert not world.line_of_sight((1.45, 4.0), (1.45, 6.0), 0.0)
    world.set_door("bedroom_door", True)
    assert world.line_of_sight((1.45, 4.0), (1.45, 6.0), 0.0)
    world.add_obstacle("box", [(4.8, 1.8), (5.2, 1.8), (5.2, 2.2), (4.8, 2.2)], 0.5)
    assert not world.is_free(5.0, 2.0, 0.1)
    assert world.render().value_at(5.0, 2.0) == 0  # static map has no dynamic obstacles
    assert world.line_of_sight((4.0, 2.0), (6.0, 2.0), 1.0)  # low box doesn't occlude
    assert not world.line_of_sight((4.0, 2.0), (6.0, 2.0), 0.3)
    world.remove_obstacle("box")
    assert world.is_free(5.0, 2.0, 0.1)
    with pytest.raises(KeyError):
        world.set_door("no_such_door", False)


def test_line_of_sight_walls_and_furniture(world: World) -> None:
    assert not world.line_of_sight((2.0, 2.0), (5.0, 2.0), 0.0)  # hallway/living wall
    # the wardrobe (2.0 m) hides, the bed (0.55 m) does not hide a standing person
    assert not world.line_of_sight((3.0, 7.2), (3.95 + 1.0, 7.2), 1.7)
    assert world.line_of_sight((2.6, 6.0), (0.5, 7.5), 1.7)


def test_shipped_map_matches_fresh_render(tmp_path: Path) -> None:
    shipped = default_home_path().parent / "map.yaml"
    fresh = render_home(default_home_path(), tmp_path)
    assert load_map(shipped) == load_map(fresh)
    assert (tmp_path / "map.pgm").read_bytes() == (shipped.parent / "map.pgm").read_bytes()
    assert load_map(shipped) == World.load(default_home_path()).render(0.05)


def test_bad_home_yaml(tmp_path: Path) -> None:
    text = default_home_path().read_text()
    bad = tmp_path / "home.yaml"
    bad.write_text(text.replace("rooms: [hallway, bedroom]", "rooms: [hallway, attic]"))
    with pytest.raises(ConfigError, match="attic"):
        World.load(bad)
    bad.write_text(text.replace("kind: couch,", "kind: sofa_bed,"))
    with pytest.raises(ConfigError, match="kind"):
        World.load(bad)
    bad.write_text(text.replace("wall_height: 2.5", "wall_height: 2.5\ncolour: red"))
    with pytest.raises(ConfigError, match="colour"):
        World.load(bad)
    with pytest.raises(ConfigError, match="no such file"):
        World.load(tmp_path / "missing.yaml")
