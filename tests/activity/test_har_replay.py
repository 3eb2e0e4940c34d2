"""Real recorded motion for the simulated residents (``sim.skeletons.replay``): NTU files
and the real Kinect v1 sets read into the residents' body frame, and played by the
simulator's skeleton stream instead of the synthetic generator."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from amiro.activity.dataset import subject_body
from amiro.activity.labels import NTU_ACTION_IDS
from amiro.activity.lifting import level
from amiro.activity.motion import View, perform, to_camera
from amiro.activity.ntu import Body, SkeletonSequence, write_skeleton_file
from amiro.activity.replay import body_frame, load_motion
from amiro.activity.skeleton import J
from amiro.core.clock import SimClock
from amiro.core.config import ConfigError
from amiro.core.runtime import Runtime
from amiro.sim.config import (
    REALISTIC_SKELETONS,
    PoseSpec,
    ResidentSpec,
    SimConfig,
    SkeletonsSection,
)
from amiro.sim.simulator import build_sim
from amiro.sim.skeletons import SkeletonCamera
from shared_data import shared_data


def ntu_file(folder: Path, action: str, view: View) -> np.ndarray:
    """A 30 Hz NTU file of ``action`` seen from ``view``; returns the body-frame motion."""
    rng = np.random.default_rng(4)
    body_frames = perform(action, subject_body(2, 0), rng, fps=30.0, sitting=False)
    joints = to_camera(body_frames, view)
    name = f"S001C001P002R001A{NTU_ACTION_IDS[action]:03d}.skeleton"
    n = len(joints)
    write_skeleton_file(folder / name, SkeletonSequence(n, [Body("1", joints, np.ones(n, bool))]))
    return body_frames


def test_an_ntu_file_comes_back_in_the_body_frame_whatever_the_camera(tmp_path: Path) -> None:
    view = View(yaw=0.6, distance=3.0, height=1.4, pitch=0.3)
    performed = ntu_file(tmp_path, "drink_water", view)
    (tmp_path / "S001C001P002R001A099.skeleton").write_text("an action amiro does not know")
    motion = load_motion(tmp_path)
    assert list(motion) == ["drink_water"]
    (clip,) = motion["drink_water"]
    # The camera's yaw, pitch, height and distance are gone: the same as the performance
    # itself put in the body frame, at 15 Hz.
    np.testing.assert_allclose(clip, body_frame(performed)[::2], atol=1e-4)
    first = clip[0]
    assert np.nanmin(clip[..., 1]) == pytest.approx(0.0, abs=1e-9)  # on the floor
    assert first[J["Head"], 1] > first[J["SpineShoulder"], 1] > first[J["SpineBase"], 1] > 0.5
    np.testing.assert_allclose(first[J["SpineBase"], [0, 2]], 0.0, atol=1e-9)
    assert first[J["ShoulderRight"], 0] > 0 > first[J["ShoulderLeft"], 0]
    trunk = first[J["SpineShoulder"]] - first[J["SpineBase"]]
    assert math.degrees(math.acos(trunk[1] / np.linalg.norm(trunk))) < 1  # upright


def test_a_folder_without_an_amiro_activity_is_refused(tmp_path: Path) -> None:
    with pytest.raises(ConfigError, match="no skeleton file of an amiro activity"):
        load_motion(tmp_path)
    with pytest.raises(ConfigError, match="no such folder"):
        load_motion(tmp_path / "missing")


def test_the_resident_replays_real_kard_motion(tmp_path: Path) -> None:
    (tmp_path / "kard").symlink_to(shared_data("har", "kard"))
    sensor = SkeletonsSection(noise_m=0.0, dropout=0.0, pitch_deg=0.0, replay=tmp_path)
    runtime = Runtime(SimClock(), seed=0)
    spec = ResidentSpec(
        name="maria", pose=PoseSpec(x=7.08, y=2.0, theta=math.pi), activity="drink_water"
    )
    sim = build_sim(runtime, SimConfig(start=PoseSpec(x=3.7, y=2.0), residents=[spec]))
    runtime.start()
    runtime.spin_for(0.5)
    camera = SkeletonCamera(sim, np.random.default_rng(0), sensor)
    assert len(camera.motion["drink_water"]) == 30  # KARD: 10 subjects x 3 takes
    assert camera.window("maria", 30) is not None
    stream = camera.streams["maria"]
    played = np.stack(list(stream.frames))
    # Every frame played is a frame of one of the 30 real drinking takes.
    real = np.concatenate(camera.motion["drink_water"])
    for frame in played[:: len(played) // 5]:
        assert np.isclose(real, frame, equal_nan=True).all(axis=(1, 2)).any()


def test_the_sensor_jitters_loses_joints_and_is_pitched() -> None:
    def scene(sensor: SkeletonsSection) -> np.ndarray:
        runtime = Runtime(SimClock(), seed=0)
        spec = ResidentSpec(name="maria", pose=PoseSpec(x=7.08, y=2.0, theta=math.pi))
        cfg = SimConfig(start=PoseSpec(x=3.7, y=2.0), residents=[spec], skeletons=sensor)
        sim = build_sim(runtime, cfg)
        runtime.start()
        runtime.spin_for(0.5)
        frames = SkeletonCamera(sim, np.random.default_rng(0)).window("maria", 60)
        assert frames is not None
        return frames

    ideal = scene(SkeletonsSection(noise_m=0.0, dropout=0.0, pitch_deg=0.0))
    realistic = SkeletonsSection(**REALISTIC_SKELETONS)
    sensed = scene(realistic)  # a real sensor
    assert realistic.pitch_deg >= 10 and realistic.noise_m > 0

    def hip_width(frames: np.ndarray) -> np.ndarray:
        return np.linalg.norm(frames[:, J["HipLeft"]] - frames[:, J["HipRight"]], axis=-1)

    assert np.nanstd(hip_width(ideal)) < 1e-6 < 0.01 < np.nanstd(hip_width(sensed))
    assert not np.isnan(ideal).any()
    lost = np.isnan(sensed[..., 0]).mean()
    assert 0.02 < lost < 0.1  # 5 % of the joints in each frame

    # The tilt is the pitch: levelling the sensed skeletons by it brings the trunk upright.
    def tilt_deg(frames: np.ndarray) -> float:
        trunk = frames[:, J["SpineShoulder"]] - frames[:, J["SpineBase"]]
        return float(np.degrees(np.nanmedian(np.arctan2(trunk[:, 2], trunk[:, 1]))))

    pitch = math.radians(realistic.pitch_deg)
    assert abs(tilt_deg(sensed) - tilt_deg(ideal)) > 10
    assert abs(tilt_deg(level(sensed, pitch)) - tilt_deg(ideal)) < 3
