"""GridMap coordinates and the ROS map_server file format."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from amiro.core.config import ConfigError
from amiro.core.gridmap import GridMap, load_map, save_map


def sample_grid() -> GridMap:
    data = np.zeros((6, 8), dtype=np.int8)
    data[0, :] = 100  # bottom row occupied
    data[5, 7] = -1  # top-right unknown
    data[2, 3] = 100
    return GridMap(data, 0.1, (-0.4, 0.2, 0.0))


def test_world_cell_round_trip_is_vectorised() -> None:
    g = sample_grid()
    cols, rows = np.array([0, 3, 7]), np.array([0, 2, 5])
    x, y = g.cell_to_world(cols, rows)
    assert np.allclose(x, [-0.35, -0.05, 0.35]) and np.allclose(y, [0.25, 0.45, 0.75])
    c2, r2 = g.world_to_cell(x, y)
    assert np.array_equal(c2, cols) and np.array_equal(r2, rows)
    assert g.value_at(-0.05, 0.45) == 100
    assert g.value_at(100.0, 0.0) == -1  # off the map reads unknown


def test_rotated_origin_conversions() -> None:
    g = GridMap(np.zeros((4, 4), dtype=np.int8), 0.5, (1.0, 2.0, np.pi / 2))
    x, y = g.cell_to_world(0, 0)
    assert np.isclose(x, 1.0 - 0.25) and np.isclose(y, 2.0 + 0.25)
    c, r = g.world_to_cell(x, y)
    assert (int(c), int(r)) == (0, 0)


def test_occupancy_grid_message() -> None:
    g = sample_grid()
    msg = g.to_occupancy_grid(stamp=3.5)
    assert msg.header.frame_id == "map" and msg.header.stamp == 3.5
    assert (msg.info.width, msg.info.height) == (8, 6)
    assert msg.data[0] == 100 and msg.data[8] == 0  # row-major, row 0 at the bottom
    assert GridMap.from_occupancy_grid(msg) == g


@pytest.mark.parametrize("fmt", ["pgm", "png"])
def test_round_trip(tmp_path: Path, fmt: str) -> None:
    g = sample_grid()
    path = save_map(g, tmp_path / "m.yaml", image_format=fmt)
    assert (tmp_path / f"m.{fmt}").is_file()
    back = load_map(path)
    assert back == g
    assert back.origin == pytest.approx(g.origin)


def test_image_top_row_is_the_far_row(tmp_path: Path) -> None:
    save_map(sample_grid(), tmp_path / "m.yaml")
    raw = (tmp_path / "m.pgm").read_bytes()
    pixels = np.frombuffer(raw[-48:], dtype=np.uint8).reshape(6, 8)
    assert (pixels[-1] == 0).all()  # the occupied bottom row is the image's last row
    assert pixels[0, 7] == 205


def write_map(tmp: Path, pixels: list[list[int]], **meta: object) -> Path:
    h, w = len(pixels), len(pixels[0])
    (tmp / "x.pgm").write_bytes(
        b"P5\n# c\n%d %d\n255\n" % (w, h) + bytes(v for row in pixels for v in row)
    )
    fields = {"image": "x.pgm", "resolution": 0.05, "origin": [0, 0, 0]} | meta
    text = "".join(f"{k}: {v}\n" for k, v in fields.items())
    (tmp / "x.yaml").write_text(text)
    return tmp / "x.yaml"


def test_thresholds_and_negate(tmp_path: Path) -> None:
    row = [0, 60, 120, 200, 254]  # darkness 1.0, .76, .53, .22, .004
    g = load_map(write_map(tmp_path, [row]))
    assert g.data[0].tolist() == [100, 100, -1, -1, 0]
    g = load_map(write_map(tmp_path, [row], occupied_thresh=0.5, free_thresh=0.3))
    assert g.data[0].tolist() == [100, 100, 100, 0, 0]
    g = load_map(write_map(tmp_path, [row], negate=1))
    assert g.data[0].tolist() == [0, -1, -1, 100, 100]


def test_ascii_pgm(tmp_path: Path) -> None:
    (tmp_path / "a.pgm").write_text("P2\n3 2\n# comment\n15\n0 15 8\n15 15 0\n")
    (tmp_path / "a.yaml").write_text("image: a.pgm\nresolution: 0.1\norigin: [1, 2, 0]\n")
    g = load_map(tmp_path / "a.yaml")
    assert g.data.tolist() == [[0, 0, 100], [100, 0, -1]]  # bottom row first


@pytest.mark.parametrize(
    ("text", "needle"),
    [
        ("image: x.pgm\nresolution: 0.05\n", "origin"),
        ("image: x.pgm\nresolution: -1\norigin: [0, 0, 0]\n", "resolution"),
        ("image: nope.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n", "not found"),
        ("image: x.pgm\nresolution: 0.05\norigin: [0, 0]\n", "origin"),
        ("image: x.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nmode: weird\n", "mode"),
        ("- just\n- a list\n", "mapping"),
        ("image: [unclosed\n", "x.yaml"),
    ],
)
def test_bad_map_files(tmp_path: Path, text: str, needle: str) -> None:
    (tmp_path / "x.pgm").write_bytes(b"P5\n1 1\n255\n\x00")
    (tmp_path / "x.yaml").write_text(text)
    with pytest.raises(ConfigError, match=needle) as info:
        load_map(tmp_path / "x.yaml")
    assert "\n" not in str(info.value)


def test_corrupt_image(tmp_path: Path) -> None:
    (tmp_path / "x.pgm").write_bytes(b"P5\n4 4\n255\n\x00")
    (tmp_path / "x.yaml").write_text("image: x.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n")
    with pytest.raises(ConfigError, match="truncated"):
        load_map(tmp_path / "x.yaml")
    with pytest.raises(ConfigError, match="no such file"):
        load_map(tmp_path / "missing.yaml")
