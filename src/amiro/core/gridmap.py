"""Occupancy grid maps and the ROS map_server file format (YAML + PGM/PNG).

A :class:`GridMap` keeps ROS conventions so maps move between amiro and ROS unchanged:
values -1 unknown, 0 free, 100 occupied; row 0 is the bottom row (at the origin) while
image files store the top row first; ``origin`` is the world pose (x, y, yaw) of the
lower-left corner of cell (0, 0).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
import yaml

from amiro.core.config import ConfigError, read_yaml
from amiro.core.messages import Header, MapMetaData, OccupancyGrid, Point, Pose, Quaternion

Int8Array = npt.NDArray[np.int8]
IntArray = npt.NDArray[np.int64]
FloatArray = npt.NDArray[np.float64]

FREE = 0
OCCUPIED = 100
UNKNOWN = -1

_MODES = ("trinary", "scale", "raw")


class GridMap:
    """A 2D occupancy grid: ``data[row, col]`` in {-1, 0..100}, row 0 at the origin."""

    def __init__(
        self,
        data: npt.ArrayLike,
        resolution: float,
        origin: tuple[float, float, float] = (0.0, 0.0, 0.0),
    ) -> None:
        arr = np.asarray(data)
        if arr.ndim != 2 or arr.size == 0:
            raise ValueError(f"grid data must be a non-empty 2D array, got shape {arr.shape}")
        if resolution <= 0:
            raise ValueError(f"resolution must be positive, got {resolution}")
        self.data: Int8Array = np.ascontiguousarray(arr, dtype=np.int8)
        self.resolution = float(resolution)
        self.origin = (float(origin[0]), float(origin[1]), float(origin[2]))
        self._cos = math.cos(self.origin[2])
        self._sin = math.sin(self.origin[2])

    @classmethod
    def empty(
        cls,
        width_m: float,
        height_m: float,
        resolution: float,
        origin: tuple[float, float, float] = (0.0, 0.0, 0.0),
        value: int = FREE,
    ) -> GridMap:
        """A grid covering ``width_m`` x ``height_m`` metres, filled with ``value``."""
        cols = round(width_m / resolution)
        rows = round(height_m / resolution)
        return cls(np.full((rows, cols), value, dtype=np.int8), resolution, origin)

    # --- shape ----------------------------------------------------------------------------
    @property
    def width(self) -> int:
        """Number of columns (cells along x)."""
        return int(self.data.shape[1])

    @property
    def height(self) -> int:
        """Number of rows (cells along y)."""
        return int(self.data.shape[0])

    def copy(self) -> GridMap:
        return GridMap(self.data.copy(), self.resolution, self.origin)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, GridMap):
            return NotImplemented
        return (
            self.data.shape == other.data.shape
            and bool(np.array_equal(self.data, other.data))
            and math.isclose(self.resolution, other.resolution)
            and np.allclose(self.origin, other.origin)
        )

    __hash__ = None  # type: ignore[assignment]

    # --- coordinates (vectorised) ---------------------------------------------------------
    def world_to_map(self, x: npt.ArrayLike, y: npt.ArrayLike) -> tuple[FloatArray, FloatArray]:
        """Continuous map coordinates in cells (col, row); cell (c, r) spans [c, c+1)."""
        dx = np.asarray(x, dtype=np.float64) - self.origin[0]
        dy = np.asarray(y, dtype=np.float64) - self.origin[1]
        u = (self._cos * dx + self._sin * dy) / self.resolution
        v = (-self._sin * dx + self._cos * dy) / self.resolution
        return u, v

    def world_to_cell(self, x: npt.ArrayLike, y: npt.ArrayLike) -> tuple[IntArray, IntArray]:
        """Integer (col, row) of the cells containing the points (may be out of bounds)."""
        u, v = self.world_to_map(x, y)
        return np.floor(u).astype(np.int64), np.floor(v).astype(np.int64)

    def cell_to_world(
        self, col: npt.ArrayLike, row: npt.ArrayLike
    ) -> tuple[FloatArray, FloatArray]:
        """World (x, y) of cell centres."""
        u = (np.asarray(col, dtype=np.float64) + 0.5) * self.resolution
        v = (np.asarray(row, dtype=np.float64) + 0.5) * self.resolution
        x = self.origin[0] + self._cos * u - self._sin * v
        y = self.origin[1] + self._sin * u + self._cos * v
        return x, y

    def in_bounds(self, col: npt.ArrayLike, row: npt.ArrayLike) -> npt.NDArray[np.bool_]:
        c = np.asarray(col)
        r = np.asarray(row)
        return (c >= 0) & (c < self.width) & (r >= 0) & (r < self.height)

    def value_at(self, x: npt.ArrayLike, y: npt.ArrayLike, outside: int = UNKNOWN) -> IntArray:
        """Cell values at world points; points off the map read ``outside``."""
        col, row = self.world_to_cell(x, y)
        inside = self.in_bounds(col, row)
        out = np.full(np.shape(col), outside, dtype=np.int64)
        out[inside] = self.data[row[inside], col[inside]]
        return out

    def cell_centres(self) -> tuple[FloatArray, FloatArray]:
        """World (x, y) of every cell centre, each shaped like ``data``."""
        rows, cols = np.indices(self.data.shape)
        return self.cell_to_world(cols, rows)

    # --- messages -------------------------------------------------------------------------
    def to_occupancy_grid(self, stamp: float, frame_id: str = "map") -> OccupancyGrid:
        origin = Pose(
            Point(self.origin[0], self.origin[1], 0.0), Quaternion.from_yaw(self.origin[2])
        )
        info = MapMetaData(self.resolution, self.width, self.height, origin)
        return OccupancyGrid(Header(stamp, frame_id), info, self.data.reshape(-1).copy())

    @classmethod
    def from_occupancy_grid(cls, msg: OccupancyGrid) -> GridMap:
        o = msg.info.origin
        data = np.asarray(msg.data, dtype=np.int8).reshape(msg.info.height, msg.info.width)
        return cls(
            data.copy(), msg.info.resolution, (o.position.x, o.position.y, o.orientation.yaw)
        )


# --- image files --------------------------------------------------------------------------


def _pgm_tokens(raw: bytes, count: int) -> tuple[list[int], int]:
    """Read ``count`` whitespace-separated integers of a PNM header, skipping comments."""
    tokens: list[int] = []
    i = 2
    n = len(raw)
    while len(tokens) < count:
        while i < n and raw[i : i + 1].isspace():
            i += 1
        if i < n and raw[i : i + 1] == b"#":
            while i < n and raw[i : i + 1] not in (b"\n", b"\r"):
                i += 1
            continue
        start = i
        while i < n and raw[i : i + 1].isdigit():
            i += 1
        if start == i:
            raise ValueError("malformed PGM header")
        tokens.append(int(raw[start:i]))
    return tokens, i + 1  # exactly one whitespace byte follows the header


def read_pgm(path: Path) -> npt.NDArray[np.float64]:
    """Pixels of a P5 (binary) or P2 (ASCII) PGM, scaled to 0..255, top row first."""
    raw = path.read_bytes()
    magic = raw[:2]
    if magic not in (b"P5", b"P2"):
        raise ValueError(f"not a PGM file (magic {magic!r})")
    (width, height, maxval), offset = _pgm_tokens(raw, 3)
    if width <= 0 or height <= 0 or not 0 < maxval < 65536:
        raise ValueError("bad PGM dimensions or maxval")
    if magic == b"P5":
        dtype = np.dtype(np.uint8) if maxval < 256 else np.dtype(">u2")
        need = width * height * dtype.itemsize
        if len(raw) - offset < need:
            raise ValueError("PGM pixel data is truncated")
        pix = np.frombuffer(raw, dtype=dtype, count=width * height, offset=offset)
    else:
        values = raw[offset:].split()
        if len(values) < width * height:
            raise ValueError("PGM pixel data is truncated")
        pix = np.array([int(v) for v in values[: width * height]], dtype=np.int64)
    return pix.reshape(height, width).astype(np.float64) * (255.0 / maxval)


def write_pgm(path: Path, pixels: npt.NDArray[np.uint8]) -> None:
    """Binary P5 PGM, top row first (deterministic bytes: no comment, no timestamp)."""
    h, w = pixels.shape
    path.write_bytes(b"P5\n%d %d\n255\n" % (w, h) + np.ascontiguousarray(pixels).tobytes())


def _read_image(path: Path) -> tuple[FloatArray, npt.NDArray[np.bool_] | None]:
    """Grey levels 0..255 (top row first) and, for images with alpha, a transparency mask."""
    if path.suffix.lower() in (".pgm", ".pnm"):
        return read_pgm(path), None
    from PIL import Image as PILImage

    with PILImage.open(path) as img:
        img.load()
        transparent = None
        if img.mode in ("LA", "RGBA", "PA") or "transparency" in img.info:
            rgba = np.asarray(img.convert("RGBA"))
            transparent = rgba[..., 3] == 0
        grey = np.asarray(img.convert("L"), dtype=np.float64)
    return grey, transparent


# --- map_server YAML ----------------------------------------------------------------------


def _field(meta: dict[str, Any], key: str, source: str, default: Any = None) -> Any:
    if key not in meta:
        if default is None:
            raise ConfigError(f"{source}: missing key '{key}'")
        return default
    return meta[key]


def _number(value: Any, key: str, source: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ConfigError(f"{source}: '{key}' must be a number, got {value!r}")
    return float(value)


def load_map(yaml_path: str | Path) -> GridMap:
    """Load a ROS map_server map (YAML pointing at a PGM or PNG image)."""
    path = Path(yaml_path)
    meta = read_yaml(path)
    src = str(path)
    if not isinstance(meta, dict):
        raise ConfigError(f"{src}: expected a mapping at the top level")
    image = _field(meta, "image", src)
    if not isinstance(image, str) or not image:
        raise ConfigError(f"{src}: 'image' must be a file name")
    resolution = _number(_field(meta, "resolution", src), "resolution", src)
    if resolution <= 0:
        raise ConfigError(f"{src}: 'resolution' must be positive, got {resolution}")
    origin_raw = _field(meta, "origin", src)
    if not isinstance(origin_raw, list | tuple) or len(origin_raw) != 3:
        raise ConfigError(f"{src}: 'origin' must be [x, y, yaw], got {origin_raw!r}")
    ox, oy, oyaw = (_number(v, "origin", src) for v in origin_raw)
    negate = _field(meta, "negate", src, 0)
    if negate not in (0, 1, True, False):
        raise ConfigError(f"{src}: 'negate' must be 0 or 1, got {negate!r}")
    occ = _number(_field(meta, "occupied_thresh", src, 0.65), "occupied_thresh", src)
    free = _number(_field(meta, "free_thresh", src, 0.196), "free_thresh", src)
    if not 0.0 <= free < occ <= 1.0:
        raise ConfigError(f"{src}: need 0 <= free_thresh < occupied_thresh <= 1")
    mode = _field(meta, "mode", src, "trinary")
    if mode not in _MODES:
        raise ConfigError(f"{src}: 'mode' must be one of {', '.join(_MODES)}, got {mode!r}")

    img_path = Path(image) if Path(image).is_absolute() else path.parent / image
    if not img_path.is_file():
        raise ConfigError(f"{src}: image file {img_path} not found")
    try:
        grey, transparent = _read_image(img_path)
    except Exception as exc:  # pillow and the PGM reader raise many types
        raise ConfigError(f"{img_path}: cannot read image: {exc}") from None

    data = _classify(grey, transparent, bool(negate), occ, free, str(mode))
    return GridMap(np.flipud(data), resolution, (ox, oy, oyaw))


def _classify(
    grey: FloatArray,
    transparent: npt.NDArray[np.bool_] | None,
    negate: bool,
    occ: float,
    free: float,
    mode: str,
) -> Int8Array:
    """Pixels to cell values with map_server's rules (p = darkness unless negated)."""
    if mode == "raw":
        data = np.clip(np.rint(grey), 0, 255).astype(np.int64)
        data = np.where(data > 100, UNKNOWN, data)
        return data.astype(np.int8)
    p = grey / 255.0 if negate else (255.0 - grey) / 255.0
    out = np.full(grey.shape, UNKNOWN, dtype=np.int8)
    out[p > occ] = OCCUPIED
    out[p < free] = FREE
    if mode == "scale":
        mid = (p >= free) & (p <= occ)
        out[mid] = np.rint(99.0 * (p[mid] - free) / (occ - free)).astype(np.int8)
    if transparent is not None:
        out[transparent] = UNKNOWN
    return out


def map_pixels(grid: GridMap) -> npt.NDArray[np.uint8]:
    """The map_saver image of ``grid`` (top row first): free 254, occupied 0, unknown 205."""
    d = grid.data.astype(np.int64)
    pix = np.full(d.shape, 205, dtype=np.uint8)
    pix[d == FREE] = 254
    pix[d == OCCUPIED] = 0
    mid = (d > 0) & (d < 100)
    pix[mid] = np.rint(255.0 * (1.0 - d[mid] / 100.0)).astype(np.uint8)
    return np.flipud(pix)


def save_map(
    grid: GridMap,
    yaml_path: str | Path,
    image_format: str = "pgm",
    occupied_thresh: float = 0.65,
    free_thresh: float = 0.196,
) -> Path:
    """Write ``grid`` as map_server trinary YAML + image (as ``map_saver`` does).

    Free cells become 254, occupied 0 and unknown 205; intermediate values are written as
    grey levels so that a ``scale`` reader recovers them approximately.
    """
    fmt = image_format.lower()
    if fmt not in ("pgm", "png"):
        raise ValueError(f"image_format must be pgm or png, got {image_format!r}")
    path = Path(yaml_path)
    path.parent.mkdir(parents=True, exist_ok=True)
    img_path = path.with_suffix(f".{fmt}")
    pix = map_pixels(grid)
    if fmt == "pgm":
        write_pgm(img_path, pix)
    else:
        from PIL import Image as PILImage

        PILImage.fromarray(np.ascontiguousarray(pix), mode="L").save(img_path)
    meta = {
        "image": img_path.name,
        "mode": "trinary",
        "resolution": grid.resolution,
        "origin": [float(v) for v in grid.origin],
        "negate": 0,
        "occupied_thresh": occupied_thresh,
        "free_thresh": free_thresh,
    }
    path.write_text(yaml.safe_dump(meta, sort_keys=False), encoding="utf-8")
    return path
