"""Whether a window ends with the person lying on the floor: the fall's confirmation.

Real daily activity (walking, carrying, picking things up, sitting down) fooled a
classifier trained on synthetic falls into 200 false alerts an hour; what it cannot fake
is the end of a fall, a body flat on the floor.  In the window's own view (bones at the
standard lengths, up along the first frame's trunk, so the camera's pitch and height are
gone) a lying body's extent along the vertical is a fraction of a standing (~1.7 m),
sitting (~1.2 m) or bending one's.
"""

from __future__ import annotations

import numpy as np

from amiro.activity.fall import FALL_LABEL
from amiro.activity.normalize import MAX_TILT, first_view, normalize_bones
from amiro.activity.skeleton import FloatArray

FLAT_M = 0.9  # vertical extent of a body down on the floor, at most


def lying(frames: FloatArray, tail: int = 2) -> bool:
    """True when the last ``tail`` frames are flat (every one of them seen)."""
    if len(frames) <= tail:  # too short to tell a posture from noise
        return False
    bones = normalize_bones(frames[-tail:])
    view = first_view(frames[0])
    # A window that starts upright is levelled by its trunk (the camera's pitch goes); one
    # that starts down already cannot tell pitch from posture: the camera's own vertical.
    up = (
        view.apply(bones)[..., 1]
        if view.rotation[1, 1] > np.cos(MAX_TILT) + 1e-6
        else bones[..., 1]
    )
    if np.isnan(up).all(axis=1).any():
        return False
    top = np.where(np.isnan(up), -np.inf, up).max(axis=1)
    bottom = np.where(np.isnan(up), np.inf, up).min(axis=1)
    return bool(np.all(top - bottom <= FLAT_M))


def confirm_fall(label: str | None, frames: FloatArray) -> str | None:
    """The model's label, but "falling" only when the body also ends flat."""
    if label == FALL_LABEL and not lying(frames):
        return None
    return label


class FallLatch:
    """Per person: after a confirmed fall, "falling" for as long as the body stays flat.

    Once down, a body half out of view on the floor no longer looks like the falls the
    model learnt (it says ``unknown``); the monitor still needs its second reading."""

    def __init__(self) -> None:
        self.down: set[str] = set()

    def __call__(self, person: str, label: str | None, frames: FloatArray) -> str | None:
        confirmed = confirm_fall(label, frames)
        if confirmed == FALL_LABEL:
            self.down.add(person)
            return confirmed
        if person in self.down and lying(frames):
            return FALL_LABEL
        self.down.discard(person)
        return confirmed
