"""The simulator's rendered head camera (``amiro sim --ros2``'s /camera/* topics): people in
sight at their true depth, hidden ones not drawn, images and intrinsics of one size."""

from __future__ import annotations

import math

import pytest

from amiro.cli import main
from amiro.core import names
from amiro.core.clock import SimClock
from amiro.core.messages import CameraInfo, Image
from amiro.core.runtime import Runtime
from amiro.deploy.config import NodeConfig, SimCameraSection
from amiro.deploy.sim_camera import SimCameraNode
from amiro.sim.config import SimConfig
from amiro.sim.simulator import build_sim

# Robot parked at "hallway" (2.0, 4.2) facing +x; ana 4 m ahead in the hallway, bob in the
# bedroom behind its wall.
SIM = SimConfig.model_validate(
    {
        "start": "hallway",
        "residents": [
            {"name": "ana", "pose": {"x": 6.0, "y": 4.2, "theta": 0.0}},
            {"name": "bob", "pose": {"x": 2.0, "y": 6.5, "theta": 0.0}},
        ],
    }
)


def test_rendered_frames_show_people_in_sight_at_their_depth() -> None:
    runtime = Runtime(SimClock(), seed=1)
    sim = build_sim(runtime, SIM)
    node = runtime.add(SimCameraNode(sim, SimCameraSection(rate_hz=5.0, width=160, height=120)))
    got: dict[str, list[object]] = {t: [] for t in (names.IMAGE, names.DEPTH, names.CAMERA_INFO)}
    for topic, kind in (
        (names.IMAGE, Image),
        (names.DEPTH, Image),
        (names.CAMERA_INFO, CameraInfo),
    ):
        runtime.bus.subscribe(topic, kind, got[topic].append)
    runtime.start()
    runtime.spin_for(1.0)
    assert [(c.x, c.y) for c in node.people_in_sight()] == [(6.0, 4.2)]
    assert 4 <= node.frames <= 6 and all(len(v) == node.frames for v in got.values())
    rgb, depth, info = got[names.IMAGE][-1], got[names.DEPTH][-1], got[names.CAMERA_INFO][-1]
    assert isinstance(rgb, Image) and isinstance(depth, Image) and isinstance(info, CameraInfo)
    sizes = {(rgb.width, rgb.height), (depth.width, depth.height), (info.width, info.height)}
    assert sizes == {(160, 120)}
    assert rgb.encoding == "rgb8" and depth.encoding == "32FC1"
    # ana's front at the camera's height (the horizon's rows; the floor is nearer below):
    # 0.08 m camera offset, 0.15 m radius.
    nearest = float(depth.data[55:65, 75:85].min())
    assert math.isclose(nearest, 6.0 - 2.0 - 0.08 - 0.15, abs_tol=0.05)


def test_sim_process_camera_adds_the_camera_topics_only_when_configured() -> None:
    plain = NodeConfig(role="sim")
    rendered = NodeConfig(role="sim", camera=SimCameraSection())
    added = set(rendered.topics_out()) - set(plain.topics_out())
    assert added == {names.IMAGE, names.DEPTH}  # camera_info is a sim default already


@pytest.mark.parametrize("size", ["320", "axb", "320x"])
def test_bad_camera_size_is_a_one_line_error(size: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["sim", "--ros2", "--camera-size", size]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--camera-size" in err
