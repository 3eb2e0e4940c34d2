"""2D pose keypoints (OpenPose BODY_25, MediaPipe BlazePose 33, COCO 17) in the NTU-25 layout.

The robot has no Kinect: as in the paper (section 3.5), a 2D pose estimator on the RGB
image gives keypoints, which are renamed and combined into the 25 Kinect v2 joints before
lifting to 3D (:mod:`amiro.activity.lifting`).  Each NTU joint is a weighted mean of source
keypoints; when a recipe's keypoints are not all confident, the next recipe is tried, and
a joint no recipe can make stays NaN (unseen), which the model handles.
"""

from __future__ import annotations

import numpy as np

from amiro.activity.skeleton import NUM_JOINTS, FloatArray, J
from amiro.core.config import ConfigError

Recipe = tuple[tuple[int, float], ...]  # (source keypoint, weight), weights sum to 1
Recipes = dict[str, tuple[Recipe, ...]]

BODY_25: tuple[str, ...] = (
    "Nose", "Neck", "RShoulder", "RElbow", "RWrist", "LShoulder", "LElbow", "LWrist",
    "MidHip", "RHip", "RKnee", "RAnkle", "LHip", "LKnee", "LAnkle", "REye", "LEye", "REar",
    "LEar", "LBigToe", "LSmallToe", "LHeel", "RBigToe", "RSmallToe", "RHeel",
)  # fmt: skip
BLAZEPOSE_33: tuple[str, ...] = (
    "nose", "left_eye_inner", "left_eye", "left_eye_outer", "right_eye_inner", "right_eye",
    "right_eye_outer", "left_ear", "right_ear", "mouth_left", "mouth_right", "left_shoulder",
    "right_shoulder", "left_elbow", "right_elbow", "left_wrist", "right_wrist", "left_pinky",
    "right_pinky", "left_index", "right_index", "left_thumb", "right_thumb", "left_hip",
    "right_hip", "left_knee", "right_knee", "left_ankle", "right_ankle", "left_heel",
    "right_heel", "left_foot_index", "right_foot_index",
)  # fmt: skip

COCO_17: tuple[str, ...] = (
    "nose", "left_eye", "right_eye", "left_ear", "right_ear", "left_shoulder",
    "right_shoulder", "left_elbow", "right_elbow", "left_wrist", "right_wrist", "left_hip",
    "right_hip", "left_knee", "right_knee", "left_ankle", "right_ankle",
)  # fmt: skip

# Kinect's SpineMid sits 0.28 m up the 0.50 m spine, its Neck 0.07 m up the 0.20 m from the
# shoulders' centre to the head centre, its hand centre and tip 0.07 and 0.13 m past the
# wrist on a 0.24 m forearm: the weights below extrapolate those from what a 2D estimator sees.
_SPINE_MID = 0.56
_NECK = 0.35
_HAND = 0.3
_TIP = 0.55


def _mean(*points: int) -> Recipe:
    return tuple((p, 1.0 / len(points)) for p in points)


def _between(a: Recipe, b: Recipe, t: float) -> Recipe:
    """The point a fraction ``t`` of the way from ``a`` to ``b`` (t > 1 extrapolates)."""
    weights: dict[int, float] = {}
    for point, w in a:
        weights[point] = weights.get(point, 0.0) + (1.0 - t) * w
    for point, w in b:
        weights[point] = weights.get(point, 0.0) + t * w
    return tuple(weights.items())


def _openpose() -> Recipes:
    k = {name: i for i, name in enumerate(BODY_25)}
    hips, neck = (k["MidHip"],), (k["Neck"],)
    head = (_mean(k["LEar"], k["REar"]), _mean(k["LEye"], k["REye"]), _mean(k["Nose"]))
    recipes: Recipes = {
        "SpineBase": (_mean(*hips), _mean(k["LHip"], k["RHip"])),
        "SpineMid": (_between(_mean(*hips), _mean(*neck), _SPINE_MID),),
        "SpineShoulder": (_mean(*neck), _mean(k["LShoulder"], k["RShoulder"])),
        "Head": head,
        "Neck": tuple(_between(_mean(*neck), h, _NECK) for h in head),
    }
    for side, s in (("Left", "L"), ("Right", "R")):
        elbow, wrist = _mean(k[s + "Elbow"]), _mean(k[s + "Wrist"])
        hand = _between(elbow, wrist, 1.0 + _HAND)
        recipes |= {
            "Shoulder" + side: (_mean(k[s + "Shoulder"]),),
            "Elbow" + side: (elbow,),
            "Wrist" + side: (wrist,),
            "Hand" + side: (hand,),
            "HandTip" + side: (_between(elbow, wrist, 1.0 + _TIP),),
            "Thumb" + side: (hand,),  # BODY_25 has no fingers: the thumb at the hand centre
            "Hip" + side: (_mean(k[s + "Hip"]),),
            "Knee" + side: (_mean(k[s + "Knee"]),),
            "Ankle" + side: (_mean(k[s + "Ankle"]),),
            "Foot" + side: (_mean(k[s + "BigToe"], k[s + "SmallToe"]), _mean(k[s + "BigToe"])),
        }
    return recipes


def _trunk(k: dict[str, int], head: tuple[Recipe, ...]) -> Recipes:
    """Spine, head and neck of a format naming its hips and shoulders like COCO does."""
    hips = _mean(k["left_hip"], k["right_hip"])
    shoulders = _mean(k["left_shoulder"], k["right_shoulder"])
    return {
        "SpineBase": (hips,),
        "SpineMid": (_between(hips, shoulders, _SPINE_MID),),
        "SpineShoulder": (shoulders,),
        "Head": head,
        "Neck": tuple(_between(shoulders, h, _NECK) for h in head),
    }


def _blazepose() -> Recipes:
    k = {name: i for i, name in enumerate(BLAZEPOSE_33)}
    recipes = _trunk(k, (_mean(k["left_ear"], k["right_ear"]), _mean(k["nose"])))
    for side in ("Left", "Right"):
        s = side.lower() + "_"
        recipes |= {
            "Shoulder" + side: (_mean(k[s + "shoulder"]),),
            "Elbow" + side: (_mean(k[s + "elbow"]),),
            "Wrist" + side: (_mean(k[s + "wrist"]),),
            "Hand" + side: (_mean(k[s + "wrist"], k[s + "pinky"], k[s + "index"]),),
            "HandTip" + side: (_mean(k[s + "index"]),),
            "Thumb" + side: (_mean(k[s + "thumb"]),),
            "Hip" + side: (_mean(k[s + "hip"]),),
            "Knee" + side: (_mean(k[s + "knee"]),),
            "Ankle" + side: (_mean(k[s + "ankle"]),),
            "Foot" + side: (_mean(k[s + "foot_index"]), _mean(k[s + "heel"])),
        }
    return recipes


def _coco() -> Recipes:
    """COCO's 17 keypoints (YOLO-pose, RTMPose, ViTPose...): no feet, so FootLeft and
    FootRight stay unseen; hands extrapolated along the forearm as for BODY_25."""
    k = {name: i for i, name in enumerate(COCO_17)}
    head = (
        _mean(k["left_ear"], k["right_ear"]),
        _mean(k["left_eye"], k["right_eye"]),
        _mean(k["nose"]),
    )
    recipes = _trunk(k, head)
    for side in ("Left", "Right"):
        s = side.lower() + "_"
        elbow, wrist = _mean(k[s + "elbow"]), _mean(k[s + "wrist"])
        hand = _between(elbow, wrist, 1.0 + _HAND)
        recipes |= {
            "Shoulder" + side: (_mean(k[s + "shoulder"]),),
            "Elbow" + side: (elbow,),
            "Wrist" + side: (wrist,),
            "Hand" + side: (hand,),
            "HandTip" + side: (_between(elbow, wrist, 1.0 + _TIP),),
            "Thumb" + side: (hand,),
            "Hip" + side: (_mean(k[s + "hip"]),),
            "Knee" + side: (_mean(k[s + "knee"]),),
            "Ankle" + side: (_mean(k[s + "ankle"]),),
        }
    return recipes


FORMATS: dict[str, tuple[tuple[str, ...], Recipes]] = {
    "openpose_body25": (BODY_25, _openpose()),
    "mediapipe_blazepose33": (BLAZEPOSE_33, _blazepose()),
    "coco17": (COCO_17, _coco()),
}


def to_ntu(keypoints: FloatArray, fmt: str, min_confidence: float = 0.3) -> FloatArray:
    """Keypoints ``(frames, K, 3)`` of (u, v, confidence) in ``fmt`` to NTU-25 pixel
    positions ``(frames, 25, 2)``, NaN where no recipe's keypoints are all confident."""
    if fmt not in FORMATS:
        raise ConfigError(f"unknown keypoint format {fmt!r} (known: {', '.join(FORMATS)})")
    names, recipes = FORMATS[fmt]
    if keypoints.ndim != 3 or keypoints.shape[1:] != (len(names), 3):
        raise ConfigError(
            f"{fmt} keypoints must have shape (frames, {len(names)}, 3), got {keypoints.shape}"
        )
    ok = (keypoints[..., 2] >= min_confidence) & np.isfinite(keypoints).all(axis=-1)
    out = np.full((len(keypoints), NUM_JOINTS, 2), np.nan)
    for joint, options in recipes.items():
        todo = np.ones(len(keypoints), bool)
        for recipe in options:
            points = [p for p, _ in recipe]
            usable = todo & ok[:, points].all(axis=1)
            weights = np.array([w for _, w in recipe])
            out[usable, J[joint]] = np.einsum(
                "k,tkc->tc", weights, keypoints[usable][:, points, :2]
            )
            todo &= ~usable
    return out
