"""The simulated residents' skeleton streams as the head camera sees them."""

import math
from typing import Any

import numpy as np

from amiro.activity.skeleton import NUM_JOINTS, J, visible
from amiro.core.clock import SimClock
from amiro.core.runtime import Runtime
from amiro.sim.config import PoseSpec, ResidentSpec, SimConfig, SkeletonsSection
from amiro.sim.simulator import Simulation, build_sim
from amiro.sim.skeletons import OCCLUSION_VISIBLE, SkeletonCamera

PERSON_X = 7.08


def _scene(distance: float, **resident: Any) -> tuple[Runtime, Simulation, SkeletonCamera]:
    runtime = Runtime(SimClock(), seed=0)
    spec = ResidentSpec(
        name="maria",
        pose=PoseSpec(x=PERSON_X, y=2.0, theta=math.pi),
        **resident,
    )
    ideal = SkeletonsSection(noise_m=0.0, dropout=0.0, pitch_deg=0.0)  # the geometry alone
    cfg = SimConfig(start=PoseSpec(x=PERSON_X - distance, y=2.0), residents=[spec], skeletons=ideal)
    sim = build_sim(runtime, cfg)
    runtime.start()
    runtime.spin_for(0.5)
    return runtime, sim, SkeletonCamera(sim, np.random.default_rng(0))


def test_a_person_in_full_view_gives_a_levelled_kinect_space_skeleton() -> None:
    _, _, camera = _scene(3.4, activity="hand_waving")
    frames = camera.window("maria", 30)
    assert frames is not None and frames.shape == (30, NUM_JOINTS, 3)
    assert visible(frames).all()
    base, head = frames[:, J["SpineBase"]], frames[:, J["Head"]]
    # z away from the camera (standing, the person steps ~0.4 m forward of their spot)
    assert np.all((base[:, 2] > 2.8) & (base[:, 2] < 3.5))
    assert np.all(head[:, 1] - base[:, 1] > 0.5)  # y up, whatever the head's pitch
    assert np.all(np.abs(base[:, 0]) < 0.2)  # straight ahead
    framing = camera.framing("maria")
    assert framing is not None and 0.45 < framing[0] < 0.85 and not framing[1]


def test_too_close_the_image_cuts_the_legs_and_the_box_is_clipped() -> None:
    _, _, camera = _scene(1.5)
    frames = camera.window("maria", 10)
    assert frames is not None
    seen = visible(frames)
    assert not seen[:, [J["FootLeft"], J["KneeRight"], J["Head"]]].any()
    assert seen[:, J["SpineMid"]].all()
    assert camera.framing("maria") == (1.0, True)


def test_an_occluded_skeleton_keeps_only_the_head_and_shoulders() -> None:
    _, _, camera = _scene(3.4, skeleton_occluded=True)
    frames = camera.window("maria", 5)
    assert frames is not None
    assert np.flatnonzero(visible(frames).all(axis=0)).tolist() == sorted(OCCLUSION_VISIBLE)


def test_the_stream_advances_with_simulated_time_at_the_model_rate() -> None:
    runtime, _, camera = _scene(3.4, activity="typing", posture="standing")
    before = camera.window("maria", 30)
    runtime.spin_for(1.0)  # 15 new frames at 15 Hz
    after = camera.window("maria", 30)
    assert before is not None and after is not None
    np.testing.assert_allclose(after[:15], before[15:], atol=1e-9)
    assert not np.allclose(after[15:], before[15:])


def test_after_a_fall_the_person_lies_still_and_unseen_people_give_nothing() -> None:
    runtime, sim, camera = _scene(3.4)
    standing = camera.window("maria", 1)  # watched while idle, then she falls
    sim.residents.residents["maria"].activity = "falling"
    runtime.spin_for(6.0)
    frames = camera.window("maria", 10)
    assert standing is not None and frames is not None
    np.testing.assert_array_equal(frames[0], frames[-1])
    highest_seen = np.nanmax(frames[-1, :, 1])  # the head may have fallen out of the image
    assert standing[0, J["Head"], 1] - highest_seen > 1.0
    assert camera.window("nobody", 10) is None and camera.framing("nobody") is None
