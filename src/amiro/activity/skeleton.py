"""The NTU RGB+D / Kinect v2 skeleton: 25 joints, their tree and standard segment lengths.

Every skeleton in amiro is an array ``(frames, 25, 3)`` in Kinect camera space (metres,
x to the sensor's left, y up, z away from the sensor), with NaN for a joint not seen.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]
BoolArray = npt.NDArray[np.bool_]

JOINTS: tuple[str, ...] = (
    "SpineBase",
    "SpineMid",
    "Neck",
    "Head",
    "ShoulderLeft",
    "ElbowLeft",
    "WristLeft",
    "HandLeft",
    "ShoulderRight",
    "ElbowRight",
    "WristRight",
    "HandRight",
    "HipLeft",
    "KneeLeft",
    "AnkleLeft",
    "FootLeft",
    "HipRight",
    "KneeRight",
    "AnkleRight",
    "FootRight",
    "SpineShoulder",
    "HandTipLeft",
    "ThumbLeft",
    "HandTipRight",
    "ThumbRight",
)
NUM_JOINTS = len(JOINTS)
J = {name: i for i, name in enumerate(JOINTS)}

# Parent of every joint in the Kinect v2 tree (the root, SpineBase, has none).
PARENT: tuple[int, ...] = (
    -1, 0, 20, 2, 20, 4, 5, 6, 20, 8, 9, 10, 0, 12, 13, 14, 0, 16, 17, 18, 1, 7, 6, 11, 10,
)  # fmt: skip

# Standard length (m) of the segment from each joint's parent to the joint: adult averages
# of Kinect v2 skeletons (the scale of NTU RGB+D), the target of bone normalisation.
SEGMENT_LENGTH: tuple[float, ...] = (
    0.0, 0.28, 0.07, 0.13, 0.17, 0.26, 0.24, 0.07, 0.17, 0.26, 0.24, 0.07,
    0.08, 0.38, 0.37, 0.10, 0.08, 0.38, 0.37, 0.10, 0.22, 0.06, 0.05, 0.06, 0.05,
)  # fmt: skip


def _depth(j: int) -> int:
    d = 0
    while PARENT[j] >= 0:
        j = PARENT[j]
        d += 1
    return d


def _path(j: int) -> list[int]:
    """Joints from just below the root down to ``j`` (the bones on the way)."""
    out = []
    while j > 0:
        out.append(j)
        j = PARENT[j]
    return out


DEPTH = np.array([_depth(j) for j in range(NUM_JOINTS)])
# PATH[j, k] = 1 when the bone ending at k lies on the root-to-j path (k == j included).
PATH = np.zeros((NUM_JOINTS, NUM_JOINTS))
for _j in range(NUM_JOINTS):
    PATH[_j, _path(_j)] = 1.0
# Standard distance from the root to each joint along the tree.
ROOT_DISTANCE = PATH @ np.array(SEGMENT_LENGTH)


def visible(frames: FloatArray) -> BoolArray:
    """Which joints of each frame were seen: ``(frames, 25)``."""
    seen: BoolArray = ~np.isnan(frames.sum(axis=-1))  # one NaN coordinate makes the sum NaN
    return seen
