"""Joint-dropout and occlusion augmentation, so partial skeletons still classify.

The paper (section 5) saw OpenPose lose joints when the robot stood too close or a
chair hid the person; these transforms show the model such skeletons while it trains.
"""

from __future__ import annotations

import numpy as np

from amiro.activity.skeleton import JOINTS, NUM_JOINTS, FloatArray, J

REGIONS: dict[str, tuple[int, ...]] = {
    "legs": tuple(J[n] for s in ("Left", "Right") for n in (f"Knee{s}", f"Ankle{s}", f"Foot{s}")),
    "lower_body": tuple(
        J[n]
        for n in (
            "SpineBase",
            "HipLeft",
            "HipRight",
            *(f"{j}{s}" for s in ("Left", "Right") for j in ("Knee", "Ankle", "Foot")),
        )
    ),
    "left_arm": tuple(
        J[n] for n in ("ElbowLeft", "WristLeft", "HandLeft", "HandTipLeft", "ThumbLeft")
    ),
    "right_arm": tuple(
        J[n] for n in ("ElbowRight", "WristRight", "HandRight", "HandTipRight", "ThumbRight")
    ),
    "head": (J["Head"], J["Neck"]),
}


# Each joint's mirror image: left and right swapped.
MIRROR = tuple(
    J[n.replace("Left", "Right")] if "Left" in n else J[n.replace("Right", "Left")] for n in JOINTS
)


def mirror(frames: FloatArray) -> FloatArray:
    """The mirror image across the sensor's x = 0 plane: a right-handed performance
    becomes a left-handed one."""
    out = frames[:, list(MIRROR)].copy()
    out[..., 0] *= -1.0
    return out


def drop_joints(frames: FloatArray, fraction: float, rng: np.random.Generator) -> FloatArray:
    """The same randomly chosen ``fraction`` of joints unseen in every frame."""
    out = frames.copy()
    count = round(fraction * NUM_JOINTS)
    out[:, rng.choice(NUM_JOINTS, size=count, replace=False)] = np.nan
    return out


def flicker(frames: FloatArray, fraction: float, rng: np.random.Generator) -> FloatArray:
    """Each joint of each frame independently unseen with probability ``fraction``."""
    out = frames.copy()
    out[rng.random(frames.shape[:2]) < fraction] = np.nan
    return out


def occlude(frames: FloatArray, rng: np.random.Generator) -> FloatArray:
    """One body region hidden, over the whole window or a stretch of it."""
    out = frames.copy()
    names = list(REGIONS)
    region = REGIONS[names[int(rng.integers(len(names)))]]
    n = len(frames)
    start, stop = (0, n) if rng.random() < 0.5 else sorted(rng.integers(0, n + 1, 2))
    out[start:stop, list(region)] = np.nan
    return out


def augment(frames: FloatArray, rng: np.random.Generator) -> FloatArray:
    """A random mix: untouched, fixed dropout, flicker or a region occluded."""
    pick = rng.random()
    if pick < 0.2:
        return frames
    if pick < 0.6:
        return drop_joints(frames, rng.uniform(0.05, 0.55), rng)
    if pick < 0.75:
        return flicker(frames, rng.uniform(0.05, 0.4), rng)
    return occlude(frames, rng)


def time_warp(
    frames: FloatArray, length: int, speed: float, rng: np.random.Generator
) -> FloatArray:
    """``length`` frames of the motion played ``speed`` times as fast: a random stretch of
    ``length * speed`` source frames (as many as there are at most), linearly resampled.
    Real sets record at other rates and people move at their own pace."""
    span = int(np.clip(round(length * speed), 2, len(frames)))
    start = int(rng.integers(0, len(frames) - span + 1))
    t = start + np.linspace(0.0, span - 1.0, length)
    i0 = np.minimum(np.floor(t).astype(int), len(frames) - 2)
    share = (t - i0)[:, None, None]
    out: FloatArray = (1.0 - share) * frames[i0] + share * frames[i0 + 1]
    return out


# The joints a Kinect v1 never gives (see kinect_v1.py): real training data lacks them, so
# synthetic windows sometimes do too, and the model learns not to rely on them.
KINECT_V1_UNSEEN = tuple(
    J[n] for s in ("Left", "Right") for n in (f"HandTip{s}", f"Thumb{s}", f"Foot{s}")
)


def pitch(frames: FloatArray, angle: float) -> FloatArray:
    """The skeleton as a camera pitched by ``angle`` (rad, about its x axis) sees it."""
    c, s = np.cos(angle), np.sin(angle)
    y, z = frames[..., 1], frames[..., 2]
    out: FloatArray = np.stack([frames[..., 0], c * y - s * z, s * y + c * z], axis=-1)
    return out


def augment_real(
    frames: FloatArray, rng: np.random.Generator, pitch_rad: float = 0.5
) -> FloatArray:
    """A real window made new: mirrored (the other hand) half the time, another camera
    pitch, up to 2 cm of jitter, then :func:`augment`'s missing joints."""
    out = mirror(frames) if rng.random() < 0.5 else frames
    out = pitch(out, rng.uniform(-pitch_rad, pitch_rad))
    out = out + rng.normal(0.0, rng.uniform(0.0, 0.02), out.shape)
    return augment(out, rng)


def augment_synthetic(frames: FloatArray, rng: np.random.Generator) -> FloatArray:
    """Half the synthetic windows without the joints a Kinect v1 lacks, then :func:`augment`."""
    if rng.random() < 0.5:
        frames = frames.copy()
        frames[:, list(KINECT_V1_UNSEEN)] = np.nan
    return augment(frames, rng)
