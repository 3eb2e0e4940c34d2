"""``amiro perception bench`` and the real-data localisation path it times."""

from __future__ import annotations

import argparse
import json

import numpy as np
import pytest

from amiro.cli import _Parser
from amiro.commands.perception import register
from amiro.core.config import ConfigError
from amiro.core.messages import BoundingBox2D
from amiro.perception.estimation import CameraGeometry, Views
from amiro.perception.locate import locate_people
from amiro.robot.camera import Camera
from amiro.sim.rgbd_dataset import DatasetSpec, generate


def run_cli(argv: list[str]) -> int:
    parser = _Parser(prog="amiro")
    register(parser.add_subparsers(dest="command", parser_class=_Parser))
    args: argparse.Namespace = parser.parse_args(argv)
    code: int = args.handler(args)
    return code


def test_bench_reports_both_timings(capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["perception", "bench", "--frames", "5", "--repeats", "1", "--json"]
    assert run_cli(argv) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["people_per_frame"] == 3
    for key in ("estimate_ms_per_frame", "face_ms_per_face_in_frame", "face_ms_per_face_crop"):
        assert report[key] > 0
    with pytest.raises(ConfigError, match="at least 1"):
        run_cli(["perception", "bench", "--people", "0"])


def test_locate_people_on_generated_frames() -> None:
    camera = Camera()
    geom = CameraGeometry.from_info(camera.info(0.0), camera.params.height, camera.params.forward)
    batch = next(generate(np.random.default_rng(3), DatasetSpec(people=1, images=1, batch=25)))
    for i in range(5):  # 2 m, standing, facing the camera: the five camera placements
        rows = slice(i, i + 1)
        view = Views(
            batch.views.x[rows],
            batch.views.y[rows],
            batch.views.theta[rows],
            batch.views.head_yaw[rows],
            batch.views.head_pitch[rows],
        )
        box = BoundingBox2D(*map(float, batch.box[i]))
        (point,) = locate_people(geom, batch.depth[i].astype(np.float64), [box], view)
        np.testing.assert_allclose(point, batch.truth[i], atol=0.15)
    empty = np.zeros_like(batch.depth[0], dtype=np.float64)
    (nothing,) = locate_people(geom, empty, [box], view)
    assert np.isnan(nothing).all()
