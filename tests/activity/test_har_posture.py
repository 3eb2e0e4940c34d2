"""The fall confirmation: a body flat on the floor, whatever the camera's pitch."""

from __future__ import annotations

import numpy as np

from amiro.activity.labels import ACTIONS, IDLE
from amiro.activity.motion import Body, View, perform, to_camera
from amiro.activity.posture import FallLatch, confirm_fall, lying


def _fall_stream(seed: int) -> np.ndarray:
    """Standing, then a fall, then lying still."""
    rng = np.random.default_rng(seed)
    body = Body.random(rng)
    before = np.concatenate([perform(IDLE, body, rng, sitting=False) for _ in range(2)])
    fall = perform("falling", body, rng)
    return np.concatenate([before, fall, np.repeat(fall[-1:], 30, axis=0)])


def test_a_fall_ends_lying_whatever_the_camera_pitch() -> None:
    for seed in range(4):
        stream = _fall_stream(seed)
        for pitch in (0.0, 0.3):
            seen = to_camera(stream, View(yaw=0.7 * seed, pitch=pitch, height=1.2))
            assert lying(seen[-30:])
            assert confirm_fall("falling", seen[-30:]) == "falling"
            latch = FallLatch()
            assert latch("maria", None, seen[-30:]) is None  # down, but no fall seen
            assert latch("maria", "falling", seen[-30:]) == "falling"
            assert latch("maria", None, seen[-30:]) == "falling"  # still down
            assert latch("maria", "typing", seen[:30]) == "typing"  # up again
            assert latch("maria", None, seen[-30:]) is None
            assert not lying(seen[:30])  # standing before it


def test_no_other_action_ends_flat() -> None:
    rng = np.random.default_rng(7)
    body = Body.random(rng)
    for action in (*ACTIONS[:-1], IDLE):
        for sitting in (False, True):
            if action == "standing_up" and not sitting:
                continue
            frames = to_camera(perform(action, body, rng, sitting=sitting), View(pitch=0.3))
            assert not lying(frames[-30:]), action
            assert confirm_fall("falling", frames[-30:]) is None
    assert confirm_fall("drink_water", frames[-30:]) == "drink_water"
    assert not lying(frames[:2])
