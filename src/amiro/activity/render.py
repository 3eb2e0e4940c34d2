"""What a robot without a Kinect gets from a skeleton: 2D pose keypoints and a depth image.

The paper's pipeline (section 3.5) runs a 2D pose estimator on the RGB image and lifts its
keypoints with the registered depth image.  This module plays the camera and the estimator
for a known skeleton, so that pipeline (:mod:`amiro.activity.keypoints`,
:mod:`amiro.activity.lifting`) can be tested and scored: OpenPose BODY_25 keypoints where
the joints project, and a depth image in which each joint is a small patch at its depth
in front of a wall, nearer patches hiding farther ones as a real depth camera's would.
"""

from __future__ import annotations

import numpy as np

from amiro.activity.keypoints import BODY_25, COCO_17, to_ntu
from amiro.activity.lifting import level, lift_sequence
from amiro.activity.skeleton import FloatArray, J
from amiro.core.messages import CameraInfo

# The NTU joint each BODY_25 keypoint sits on (the face points on the head centre).
BODY_25_SOURCE: dict[str, str] = {
    "Nose": "Head",
    "Neck": "SpineShoulder",
    "MidHip": "SpineBase",
    "REye": "Head",
    "LEye": "Head",
    "REar": "Head",
    "LEar": "Head",
    **{s + part: part + side for s, side in (("R", "Right"), ("L", "Left"))
       for part in ("Shoulder", "Elbow", "Wrist", "Hip", "Knee", "Ankle")},
    **{s + toe: "Foot" + side for s, side in (("R", "Right"), ("L", "Left"))
       for toe in ("BigToe", "SmallToe", "Heel")},
}  # fmt: skip
_BODY_25_JOINTS = [J[BODY_25_SOURCE[name]] for name in BODY_25]
# The NTU joint each COCO-17 keypoint sits on ("left_wrist" on WristLeft; the face on Head).
_COCO_17_JOINTS = [
    J["Head"] if name.endswith(("nose", "eye", "ear"))
    else J["".join(part.title() for part in reversed(name.split("_")))]
    for name in COCO_17
]  # fmt: skip
SOURCES = {"openpose_body25": _BODY_25_JOINTS, "coco17": _COCO_17_JOINTS}


def project(joints: FloatArray, info: CameraInfo) -> FloatArray:
    """Pixels ``(..., 25, 2)`` of Kinect-space joints (x left, y up, z forward)."""
    z = joints[..., 2]
    u = info.cx - info.fx * joints[..., 0] / z
    v = info.cy - info.fy * joints[..., 1] / z
    out: FloatArray = np.stack([u, v], axis=-1)
    return out


def body25_keypoints(
    pixels: FloatArray, width: int, height: int, fmt: str = "openpose_body25"
) -> FloatArray:
    """Keypoints ``(frames, K, 3)`` (u, v, confidence) of ``fmt`` (BODY_25, or ``coco17``)
    on NTU joint pixels; a joint outside the image, or unseen, gets confidence 0."""
    uv = pixels[:, SOURCES[fmt]]
    inside = (uv[..., 0] >= 0) & (uv[..., 0] < width) & (uv[..., 1] >= 0) & (uv[..., 1] < height)
    confidence = (inside & np.isfinite(uv).all(axis=-1)).astype(np.float64)
    out: FloatArray = np.concatenate([np.nan_to_num(uv)[..., :2], confidence[..., None]], axis=-1)
    return out


def depth_image(
    joints: FloatArray, info: CameraInfo, scale: float = 0.5, wall_m: float = 6.0, half: int = 3
) -> FloatArray:
    """A depth image (``scale`` times the RGB resolution, registered to it) of one frame
    of joints: a ``2 half + 1`` pixel square per joint at its depth, nearest on top."""
    depth = np.full((round(info.height * scale), round(info.width * scale)), wall_m)
    pixels = project(joints, info) * scale
    for j in np.argsort(-np.nan_to_num(joints[:, 2], nan=-np.inf)):
        if not np.isfinite(pixels[j]).all() or joints[j, 2] <= 0:
            continue
        c, r = int(pixels[j, 0]), int(pixels[j, 1])
        if 0 <= r < depth.shape[0] and 0 <= c < depth.shape[1]:
            depth[max(r - half, 0) : r + half + 1, max(c - half, 0) : c + half + 1] = joints[j, 2]
    return depth


def through_pose_estimator(
    frames: FloatArray, info: CameraInfo, fmt: str = "openpose_body25", pitch: float = 0.0
) -> FloatArray:
    """Skeletons ``(frames, 25, 3)`` as the robot would rebuild them with its head pitched
    down by ``pitch``: ``fmt`` keypoints (BODY_25 or COCO-17), mapped to NTU-25, lifted with
    the depth image of the same instant, levelled again."""
    seen = level(frames, -pitch)
    keypoints = body25_keypoints(project(seen, info), info.width, info.height, fmt)
    stamps = np.arange(len(frames), dtype=np.float64)
    depths = [depth_image(f, info) for f in seen]
    return level(lift_sequence(to_ntu(keypoints, fmt), stamps, depths, stamps, info), pitch)
