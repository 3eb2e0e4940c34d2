"""2D NTU-layout keypoints to 3D Kinect-space skeletons with an aligned depth image.

Section 3.5 of the paper: the pose estimator runs on the RGB image, so each joint's
distance comes from the depth camera, which needs a spatial alignment (the depth image is
registered to the RGB view, possibly at another resolution) and a temporal one (the two
cameras run at different frame rates: each RGB frame takes the depth frame nearest in
time, and none when the nearest is too far off).  Depth near a joint mixes the limb with
what is behind it, so a joint takes the near end of its patch, and a joint far from the
body's median depth (a hand at the silhouette's edge hitting the wall) is dropped.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from amiro.activity.skeleton import NUM_JOINTS, FloatArray
from amiro.core.config import ConfigError
from amiro.core.messages import CameraInfo

IntArray = npt.NDArray[np.int64]


def nearest_in_time(query: FloatArray, stamps: FloatArray, max_skew_s: float) -> IntArray:
    """Index of the frame in ``stamps`` (sorted) nearest in time to each ``query`` stamp,
    -1 when the nearest is more than ``max_skew_s`` away."""
    ref = np.asarray(stamps, dtype=np.float64)
    q = np.asarray(query, dtype=np.float64)
    if len(ref) == 0:
        return np.full(len(q), -1, dtype=np.int64)
    if np.any(np.diff(ref) < 0):
        raise ConfigError("timestamps must be in increasing order")
    after = np.minimum(np.searchsorted(ref, q), len(ref) - 1)
    before = np.maximum(after - 1, 0)
    pick = np.where(np.abs(ref[after] - q) < np.abs(q - ref[before]), after, before)
    out: IntArray = np.where(np.abs(ref[pick] - q) <= max_skew_s, pick, -1).astype(np.int64)
    return out


def joint_depths(
    pixels: FloatArray, depth: FloatArray, scale: float, radius: int = 2, near: float = 0.25
) -> FloatArray:
    """Depth (m) under each joint ``(25, 2)`` RGB pixel: the ``near`` quantile of the valid
    readings (> 0) in a ``(2 radius + 1)``-square patch of ``depth``, NaN if none."""
    h, w = depth.shape
    offsets = np.arange(-radius, radius + 1)
    seen = np.isfinite(pixels).all(axis=1)
    cols = np.floor(np.nan_to_num(pixels[:, 0]) * scale).astype(np.int64)
    rows = np.floor(np.nan_to_num(pixels[:, 1]) * scale).astype(np.int64)
    rr = (rows[:, None, None] + offsets[None, :, None]).repeat(len(offsets), axis=2)
    cc = (cols[:, None, None] + offsets[None, None, :]).repeat(len(offsets), axis=1)
    inside = (rr >= 0) & (rr < h) & (cc >= 0) & (cc < w)
    values = depth[rr.clip(0, h - 1), cc.clip(0, w - 1)].reshape(len(pixels), -1)
    valid = inside.reshape(len(pixels), -1) & np.isfinite(values) & (values > 0)
    ordered = np.sort(np.where(valid, values, np.inf), axis=1)
    count = valid.sum(axis=1)
    pick = np.floor(near * np.maximum(count - 1, 0)).astype(np.int64)
    out: FloatArray = np.where(
        seen & (count > 0), np.take_along_axis(ordered, pick[:, None], 1)[:, 0], np.nan
    )
    return out


def lift_frame(
    pixels: FloatArray,
    depth: FloatArray,
    info: CameraInfo,
    max_spread_m: float = 0.8,
    radius: int = 2,
) -> FloatArray:
    """One frame of NTU-layout pixels ``(25, 2)`` to Kinect camera space ``(25, 3)`` (x
    left, y up, z forward, m) with a depth image registered to the RGB view."""
    if pixels.shape != (NUM_JOINTS, 2):
        raise ConfigError(f"keypoints must have shape (25, 2), got {pixels.shape}")
    if depth.ndim != 2 or depth.size == 0:
        raise ConfigError(f"depth image must be a 2D array, got shape {depth.shape}")
    z = joint_depths(pixels, depth, depth.shape[1] / info.width, radius)
    if np.isfinite(z).any():
        z[np.abs(z - np.nanmedian(z)) > max_spread_m] = np.nan
    x_optical = (pixels[:, 0] - info.cx) * z / info.fx
    y_optical = (pixels[:, 1] - info.cy) * z / info.fy
    out: FloatArray = np.stack([-x_optical, -y_optical, z], axis=1)
    out[~np.isfinite(z)] = np.nan
    return out


def lift_sequence(
    pixels: FloatArray,
    rgb_stamps: FloatArray,
    depths: Sequence[FloatArray],
    depth_stamps: FloatArray,
    info: CameraInfo,
    max_skew_s: float | None = None,
) -> FloatArray:
    """RGB-rate keypoints ``(frames, 25, 2)`` to skeletons ``(frames, 25, 3)``, each frame
    lifted with the depth image nearest in time; a frame with no depth image within
    ``max_skew_s`` (default: half the depth stream's median period) is all NaN."""
    if len(depths) != len(depth_stamps):
        raise ConfigError(f"{len(depths)} depth images but {len(depth_stamps)} timestamps")
    if len(pixels) != len(rgb_stamps):
        raise ConfigError(f"{len(pixels)} keypoint frames but {len(rgb_stamps)} timestamps")
    if max_skew_s is None:
        period = float(np.median(np.diff(depth_stamps))) if len(depth_stamps) > 1 else 0.0
        max_skew_s = period / 2.0 + 1e-6
    match = nearest_in_time(rgb_stamps, depth_stamps, max_skew_s)
    out = np.full((len(pixels), NUM_JOINTS, 3), np.nan)
    for i, k in enumerate(match):
        if k >= 0:
            out[i] = lift_frame(pixels[i], depths[k], info)
    return out


def resample(frames: FloatArray, stamps: FloatArray, fps: float) -> FloatArray:
    """Frames at any rate to ``fps`` (the model's), each tick taking the nearest frame."""
    if len(frames) == 0:
        return frames
    ticks = np.arange(stamps[0], stamps[-1] + 1e-9, 1.0 / fps)
    pick = nearest_in_time(ticks, np.asarray(stamps, dtype=np.float64), np.inf)
    out: FloatArray = frames[pick]
    return out


def level(joints: FloatArray, pitch: float) -> FloatArray:
    """Kinect-axes joints (x left, y up, z forward) of a camera pitched down by ``pitch``
    in the levelled frame (y straight up), the view the activity model was trained on;
    ``-pitch`` turns levelled joints into what the pitched camera sees."""
    cp, sp = np.cos(pitch), np.sin(pitch)
    y, z = joints[..., 1], joints[..., 2]
    out: FloatArray = np.stack([joints[..., 0], y * cp - z * sp, z * cp + y * sp], axis=-1)
    return out
