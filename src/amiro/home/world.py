"""The simulated home: rooms, places, walls, doors, furniture and dynamic obstacles.

The home is described by a semantic YAML (``data/homes/<name>/home.yaml``); :class:`World`
rasterises it into a static map for planners and a *live* occupancy and height layer that the
simulated sensors read, so that closing a door or dropping a box shows up in the scans.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Literal

import numpy as np
import numpy.typing as npt
from pydantic import Field, model_validator

from amiro.core.config import ConfigError, Section, load
from amiro.core.geometry import Vec2, points_in_polygon, thick_segment_mask
from amiro.core.gridmap import FREE, OCCUPIED, GridMap, save_map
from amiro.core.messages import Pose2D

FloatArray = npt.NDArray[np.float64]
BoolArray = npt.NDArray[np.bool_]

MAP_MARGIN = 0.25  # metres of map around the home's outline, so outer walls fit
DOOR_HEIGHT = 2.0


# --- the home description ---------------------------------------------------------------


class PlaceSpec(Section):
    x: float
    y: float
    theta: float = 0.0


class RoomSpec(Section):
    polygon: list[Vec2] = Field(min_length=3)


class WallSpec(Section):
    a: Vec2
    b: Vec2
    thickness: float = Field(default=0.1, gt=0.0)


class DoorSpec(Section):
    name: str
    rooms: tuple[str, str]
    a: Vec2
    b: Vec2
    open: bool = True
    thickness: float = Field(default=0.1, gt=0.0, description="panel thickness when closed")


class FurnitureSpec(Section):
    name: str
    kind: Literal["couch", "desk", "chair", "bed", "table", "counter", "wardrobe"]
    polygon: list[Vec2] = Field(min_length=3)
    height: float = Field(gt=0.0)


class LightSpec(Section):
    name: str
    kind: Literal["window", "lamp"] = "window"
    x: float
    y: float
    z: float = 1.4


class HomeSpec(Section):
    name: str
    size: tuple[float, float]
    wall_height: float = Field(default=2.5, gt=0.0)
    rooms: dict[str, RoomSpec] = Field(min_length=1)
    places: dict[str, PlaceSpec] = Field(default_factory=dict)
    seats: dict[str, PlaceSpec] = Field(default_factory=dict)
    walls: list[WallSpec] = Field(default_factory=list)
    doors: list[DoorSpec] = Field(default_factory=list)
    furniture: list[FurnitureSpec] = Field(default_factory=list)
    lights: list[LightSpec] = Field(default_factory=list)

    @model_validator(mode="after")
    def _cross_references(self) -> HomeSpec:
        if self.size[0] <= 0 or self.size[1] <= 0:
            raise ValueError("size must be positive")
        for what, names in (
            ("door", [d.name for d in self.doors]),
            ("furniture", [f.name for f in self.furniture]),
            ("light", [lt.name for lt in self.lights]),
        ):
            dupes = sorted({n for n in names if names.count(n) > 1})
            if dupes:
                raise ValueError(f"duplicate {what} name(s): {', '.join(dupes)}")
        for door in self.doors:
            for room in door.rooms:
                if room not in self.rooms:
                    raise ValueError(f"door {door.name} connects unknown room {room!r}")
        return self


# --- the world ----------------------------------------------------------------------------


class World:
    """A home with live state (doors, obstacles) and the queries sensors and tests need."""

    def __init__(self, home: HomeSpec, resolution: float = 0.05) -> None:
        self.home = home
        self.name = home.name
        self.resolution = resolution
        self.doors: dict[str, bool] = {d.name: d.open for d in home.doors}
        self.obstacles: dict[str, tuple[list[Vec2], float]] = {}
        self.version = 0  # bumped on every change of the live layer
        self._door_specs = {d.name: d for d in home.doors}
        self._room_polys = {
            n: np.asarray(r.polygon, dtype=np.float64) for n, r in home.rooms.items()
        }
        self._frame = self._blank(resolution)
        self._xs, self._ys = self._frame.cell_centres()
        self._base_height, self._base_structural = self._static_layers(resolution)
        self._live: GridMap | None = None
        self._height: FloatArray = self._base_height
        self._structural: BoolArray = self._base_structural

    @classmethod
    def load(cls, path: str | Path, resolution: float = 0.05) -> World:
        """Load a home YAML; bad content raises :class:`ConfigError` with a one-line message."""
        return cls(load(HomeSpec, path), resolution)

    # --- rasterisation ----------------------------------------------------------------
    def _blank(self, resolution: float) -> GridMap:
        w, h = self.home.size
        return GridMap.empty(
            w + 2 * MAP_MARGIN, h + 2 * MAP_MARGIN, resolution, (-MAP_MARGIN, -MAP_MARGIN, 0.0)
        )

    def _static_layers(self, resolution: float) -> tuple[FloatArray, BoolArray]:
        """Walls with door openings cut, and furniture: occluder height and 'is structure'."""
        frame = self._blank(resolution)
        xs, ys = frame.cell_centres()
        height = np.zeros(frame.data.shape, dtype=np.float64)
        structural = np.zeros(frame.data.shape, dtype=bool)
        for wall in self.home.walls:
            m = thick_segment_mask(xs, ys, wall.a, wall.b, wall.thickness, wall.thickness / 2)
            structural |= m
        max_wall = max((w.thickness for w in self.home.walls), default=0.1)
        for door in self.home.doors:
            structural &= ~thick_segment_mask(xs, ys, door.a, door.b, 2.0 * max_wall + 0.1)
        height[structural] = self.home.wall_height
        for item in self.home.furniture:
            m = points_in_polygon(xs, ys, item.polygon)
            height[m] = np.maximum(height[m], item.height)
        return height, structural

    def _door_panel(self, xs: FloatArray, ys: FloatArray, name: str) -> BoolArray:
        d = self._door_specs[name]
        return thick_segment_mask(xs, ys, d.a, d.b, d.thickness)

    def render(self, resolution: float | None = None) -> GridMap:
        """The static map (walls, closed doors, furniture) as a planner or map_server sees it."""
        res = self.resolution if resolution is None else resolution
        if math.isclose(res, self.resolution):
            frame, xs, ys = self._frame, self._xs, self._ys
            height, structural = self._base_height, self._base_structural
        else:
            frame = self._blank(res)
            xs, ys = frame.cell_centres()
            height, structural = self._static_layers(res)
        occ = structural | (height > 0.0)
        for name, is_open in self.doors.items():
            if not is_open:
                occ |= self._door_panel(xs, ys, name)
        data = np.where(occ, OCCUPIED, FREE).astype(np.int8)
        return GridMap(data, res, frame.origin)

    def _refresh(self) -> None:
        height = self._base_height.copy()
        structural = self._base_structural.copy()
        for name, is_open in self.doors.items():
            if not is_open:
                m = self._door_panel(self._xs, self._ys, name)
                height[m] = np.maximum(height[m], DOOR_HEIGHT)
                structural |= m
        for poly, h in self.obstacles.values():
            m = points_in_polygon(self._xs, self._ys, poly)
            height[m] = np.maximum(height[m], h)
        self._height, self._structural = height, structural
        data = np.where(structural | (height > 0.0), OCCUPIED, FREE).astype(np.int8)
        self._live = GridMap(data, self.resolution, self._frame.origin)

    @property
    def live(self) -> GridMap:
        """Current occupancy (doors as they are now, dynamic obstacles): what sensors see."""
        if self._live is None:
            self._refresh()
        assert self._live is not None
        return self._live

    @property
    def heights(self) -> FloatArray:
        """Current occluder height per cell of :attr:`live` (0 where free)."""
        if self._live is None:
            self._refresh()
        return self._height

    # --- live changes -----------------------------------------------------------------
    def _changed(self) -> None:
        self._live = None
        self.version += 1

    def set_door(self, name: str, open: bool) -> None:
        if name not in self.doors:
            raise KeyError(f"no door named {name!r} (doors: {', '.join(self.doors)})")
        if self.doors[name] != open:
            self.doors[name] = open
            self._changed()

    def add_obstacle(self, name: str, polygon: list[Vec2], height: float = 1.0) -> None:
        """Add (or move) a dynamic obstacle; it shows in :attr:`live`, not in :meth:`render`."""
        if len(polygon) < 3:
            raise ValueError("an obstacle polygon needs at least 3 vertices")
        self.obstacles[name] = ([(float(x), float(y)) for x, y in polygon], float(height))
        self._changed()

    def remove_obstacle(self, name: str) -> None:
        if self.obstacles.pop(name, None) is not None:
            self._changed()

    # --- queries ------------------------------------------------------------------------
    def room_at(self, x: float, y: float) -> str | None:
        for name, poly in self._room_polys.items():
            if bool(points_in_polygon(x, y, poly)):
                return name
        return None

    def room_names(self) -> list[str]:
        return list(self._room_polys)

    def room_polygon(self, name: str) -> FloatArray:
        return self._room_polys[name].copy()

    def place(self, name: str) -> Pose2D:
        """A named robot destination (dock, couch, desk, ...)."""
        try:
            p = self.home.places[name]
        except KeyError:
            raise KeyError(f"no place named {name!r}") from None
        return Pose2D(p.x, p.y, p.theta)

    def seat(self, name: str) -> Pose2D:
        """A named spot where a person sits or lies (couch_left, desk_chair, ...)."""
        try:
            p = self.home.seats[name]
        except KeyError:
            raise KeyError(f"no seat named {name!r}") from None
        return Pose2D(p.x, p.y, p.theta)

    def spot(self, name: str) -> Pose2D:
        """A seat or, failing that, a place."""
        return self.seat(name) if name in self.home.seats else self.place(name)

    def line_of_sight(
        self, p: tuple[float, float], q: tuple[float, float], min_height: float = 0.0
    ) -> bool:
        """True unless a wall, a closed door or something taller than ``min_height`` lies
        between ``p`` and ``q`` (the end cells themselves are not tested)."""
        self.live  # noqa: B018 - make sure the layers are current
        dist = math.hypot(q[0] - p[0], q[1] - p[1])
        n = max(int(dist / (self.resolution * 0.5)), 1)
        t = (np.arange(1, n) / n) if n > 1 else np.zeros(0)
        xs = p[0] + t * (q[0] - p[0])
        ys = p[1] + t * (q[1] - p[1])
        grid = self._frame
        col, row = grid.world_to_cell(xs, ys)
        inside = grid.in_bounds(col, row)
        col, row = col[inside], row[inside]
        pc, pr = grid.world_to_cell(p[0], p[1])
        qc, qr = grid.world_to_cell(q[0], q[1])
        ends = ((col == pc) & (row == pr)) | ((col == qc) & (row == qr))
        col, row = col[~ends], row[~ends]
        blocked = self._structural[row, col] | (self._height[row, col] > min_height)
        return not bool(blocked.any())

    def is_free(self, x: float, y: float, radius: float = 0.0) -> bool:
        """No occupied (or unknown) cell overlaps the disc of ``radius`` at (x, y), on the map."""
        grid = self.live
        res = grid.resolution
        n = math.ceil(radius / res) + 1
        c0, r0 = grid.world_to_cell(x, y)
        cols = np.arange(int(c0) - n, int(c0) + n + 1)
        rows = np.arange(int(r0) - n, int(r0) + n + 1)
        cc, rr = np.meshgrid(cols, rows)
        cx, cy = grid.cell_to_world(cc, rr)
        # distance from the point to each cell's square, so the disc never overlaps a cell
        gx = np.maximum(np.abs(cx - x) - 0.5 * res, 0.0)
        gy = np.maximum(np.abs(cy - y) - 0.5 * res, 0.0)
        near = np.hypot(gx, gy) < radius if radius > 0 else (gx == 0) & (gy == 0)
        cc, rr = cc[near], rr[near]
        if not bool(grid.in_bounds(cc, rr).all()):
            return False
        return not bool((grid.data[rr, cc] != FREE).any())


def default_home_path() -> Path:
    """The shipped default apartment's ``home.yaml``."""
    return Path(__file__).resolve().parents[1] / "data" / "homes" / "apartment" / "home.yaml"


def render_home(home_yaml: str | Path, out_dir: str | Path, resolution: float = 0.05) -> Path:
    """Render a home's static map as ``map.yaml`` + ``map.pgm`` (ROS map_server format)."""
    world = World.load(home_yaml, resolution)
    return save_map(world.render(resolution), Path(out_dir) / "map.yaml")


__all__ = [
    "ConfigError",
    "HomeSpec",
    "World",
    "default_home_path",
    "render_home",
]
