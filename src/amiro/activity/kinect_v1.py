"""Kinect v1 skeletons (15 or 19 joints) onto the NTU RGB+D 25-joint layout.

Real skeleton sets recorded with a Kinect v1 (OpenNI/NITE 15 joints, SDK 1.8 20 joints)
name fewer joints than NTU's Kinect v2.  The trunk joints v1 lacks are derived from what
it has (SpineBase between the hips, Neck a third of the way from SpineShoulder to the
head, a wrist or hand on the forearm's line); hand tips, thumbs and (without them) feet
cannot be derived and stay unseen (NaN).  :func:`to_ntu` also says which joints were
derived, so nothing downstream mistakes them for tracked ones.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from amiro.activity.skeleton import NUM_JOINTS, SEGMENT_LENGTH, BoolArray, FloatArray, J
from amiro.core.config import ConfigError

# Each layout: the NTU joint every source joint is, in the source's order.  The NITE
# "neck" sits between the shoulders (NTU's SpineShoulder), its "torso" at SpineMid; its
# "hand" is the hand, its "foot" the ankle.
LAYOUTS: dict[str, tuple[str, ...]] = {
    # KARD (OpenNI): head, neck, right arm, left arm, torso, right leg, left leg
    "kard": (
        "Head", "SpineShoulder", "ShoulderRight", "ElbowRight", "HandRight",
        "ShoulderLeft", "ElbowLeft", "HandLeft", "SpineMid",
        "HipRight", "KneeRight", "AnkleRight", "HipLeft", "KneeLeft", "AnkleLeft",
    ),
    # Florence 3D: wrists instead of hands, ankles, a spine joint
    "florence3d": (
        "Head", "SpineShoulder", "SpineMid", "ShoulderLeft", "ElbowLeft", "WristLeft",
        "ShoulderRight", "ElbowRight", "WristRight", "HipLeft", "KneeLeft", "AnkleLeft",
        "HipRight", "KneeRight", "AnkleRight",
    ),
    # Cornell CAD-60 (NITE): the 11 oriented joints, then hands and feet
    "cad60": (
        "Head", "SpineShoulder", "SpineMid", "ShoulderLeft", "ElbowLeft",
        "ShoulderRight", "ElbowRight", "HipLeft", "KneeLeft", "HipRight", "KneeRight",
        "HandLeft", "HandRight", "AnkleLeft", "AnkleRight",
    ),
    # CITI-DailyActivities3D (SDK 1.8 without the hip centre), order read from the data
    "citi": (
        "ShoulderLeft", "ShoulderRight", "SpineShoulder", "SpineMid", "HipLeft", "HipRight",
        "ElbowLeft", "ElbowRight", "WristLeft", "WristRight", "HandLeft", "HandRight",
        "KneeLeft", "KneeRight", "AnkleLeft", "AnkleRight", "FootLeft", "FootRight", "Head",
    ),
}  # fmt: skip

NECK_SHARE = 0.35  # NTU's Neck lies this far from SpineShoulder towards the head


@dataclass(frozen=True)
class Mapped:
    """NTU-25 frames ``(T, 25, 3)`` (metres, NaN unseen) and which joints were derived."""

    frames: FloatArray
    derived: BoolArray  # (25,): filled from other joints, not tracked by the sensor


def _on_line(frames: FloatArray, start: str, end: str, share: float) -> FloatArray:
    """A point ``share`` of the way along start -> end (beyond it when share > 1)."""
    out: FloatArray = frames[:, J[start]] + share * (frames[:, J[end]] - frames[:, J[start]])
    return out


def to_ntu(raw: FloatArray, layout: str, scale: float = 1.0) -> Mapped:
    """Source joints ``(T, n, 3)`` in ``layout`` (times ``scale`` to metres) as NTU-25."""
    if layout not in LAYOUTS:
        raise ConfigError(f"unknown skeleton layout {layout!r}; known: {', '.join(LAYOUTS)}")
    names = LAYOUTS[layout]
    if raw.ndim != 3 or raw.shape[1:] != (len(names), 3):
        raise ConfigError(f"{layout} skeletons are (frames, {len(names)}, 3), got {raw.shape}")
    frames = np.full((len(raw), NUM_JOINTS, 3), np.nan)
    frames[:, [J[n] for n in names]] = raw * scale
    have = {J[n] for n in names}
    derived = np.zeros(NUM_JOINTS, dtype=bool)

    def fill(joint: str, value: FloatArray) -> None:
        frames[:, J[joint]] = value
        derived[J[joint]] = True

    if J["SpineBase"] not in have:
        fill("SpineBase", _on_line(frames, "HipLeft", "HipRight", 0.5))
    if J["SpineMid"] not in have:
        fill("SpineMid", _on_line(frames, "SpineBase", "SpineShoulder", 0.5))
    fill("Neck", _on_line(frames, "SpineShoulder", "Head", NECK_SHARE))
    for side in ("Left", "Right"):
        forearm = SEGMENT_LENGTH[J[f"Wrist{side}"]]
        hand = SEGMENT_LENGTH[J[f"Hand{side}"]]
        if J[f"Wrist{side}"] not in have:  # the hand given: the wrist on the forearm
            share = forearm / (forearm + hand)
            fill(f"Wrist{side}", _on_line(frames, f"Elbow{side}", f"Hand{side}", share))
        if J[f"Hand{side}"] not in have:  # the wrist given: the hand beyond it
            share = 1.0 + hand / forearm
            fill(f"Hand{side}", _on_line(frames, f"Elbow{side}", f"Wrist{side}", share))
    return Mapped(frames, derived)


def resample_rate(frames: FloatArray, fps_in: float, fps_out: float) -> FloatArray:
    """Frames recorded at ``fps_in`` at ``fps_out``, each tick taking the nearest frame."""
    if len(frames) == 0:
        return frames
    ticks = np.arange(0.0, (len(frames) - 1) / fps_in + 1e-9, 1.0 / fps_out)
    pick = np.minimum(np.rint(ticks * fps_in).astype(np.intp), len(frames) - 1)
    out: FloatArray = frames[pick]
    return out
