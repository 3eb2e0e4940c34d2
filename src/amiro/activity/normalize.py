"""Skeleton preprocessing: bone lengths to the standard body, view to facing the camera.

Bone normalisation removes the subject's size (section 3.5); view normalisation removes
where the camera stood, so one model serves every robot height and viewing angle.  Both
work with missing joints: a joint whose parent is missing hangs from its nearest seen
ancestor, at the standard length of the path between them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from amiro.activity.skeleton import (
    DEPTH,
    NUM_JOINTS,
    PARENT,
    PATH,
    ROOT_DISTANCE,
    BoolArray,
    FloatArray,
    J,
    visible,
)

# ANCESTOR_RANK[j, k] = depth(k) + 1 when k is a strict ancestor of j: the deepest seen
# ancestor of j is then an argmax.
IntArray = npt.NDArray[np.intp]

ANCESTOR_RANK = np.zeros((NUM_JOINTS, NUM_JOINTS))
for _j in range(1, NUM_JOINTS):
    _k = PARENT[_j]
    while _k >= 0:
        ANCESTOR_RANK[_j, _k] = DEPTH[_k] + 1
        _k = PARENT[_k]

FEATURES_PER_FRAME = NUM_JOINTS * 4  # 3 coordinates and a seen flag per joint
# Each joint's parent; the root hangs from itself (its segment has length 0).
PARENT_OR_SELF = np.array([max(p, 0) for p in PARENT])
SEGMENT = ROOT_DISTANCE - ROOT_DISTANCE[PARENT_OR_SELF]


def _anchors(seen: BoolArray) -> tuple[IntArray, FloatArray]:
    """Per frame and joint, the deepest seen ancestor and the standard distance to it
    (the parent in frames where every joint was seen)."""
    anchor = np.broadcast_to(PARENT_OR_SELF, seen.shape).copy()
    partial = ~seen.all(axis=1)
    if partial.any():
        usable = seen[partial]
        usable[:, 0] = True  # an unseen root stands in at the centroid
        anchor[partial] = (usable[:, None, :] * ANCESTOR_RANK).argmax(axis=-1)
    target: FloatArray = ROOT_DISTANCE - ROOT_DISTANCE[anchor]
    return anchor, target


def _bones(frames: FloatArray) -> tuple[FloatArray, BoolArray]:
    """Bone-normalised positions (0 where unseen) and which joints were seen.

    A whole skeleton (the common case) hangs every joint from its parent; only skeletons
    with missing joints pay for the ancestor search and the masking."""
    seen = visible(frames)
    whole = bool(seen.all())
    if whole:
        pos = frames
        vec = pos - pos[:, PARENT_OR_SELF]
        target: FloatArray = SEGMENT
    else:
        pos = np.where(seen[..., None], frames, 0.0)
        counts = seen.sum(axis=1)
        no_root = ~seen[:, 0] & (counts > 0)
        if no_root.any():  # the root stands in at the centroid of what was seen
            pos[no_root, 0] = pos[no_root].sum(axis=1) / counts[no_root, None]
        anchor, target = _anchors(seen)
        vec = pos - np.take_along_axis(pos, anchor[..., None], axis=1)
    scale = target / np.maximum(np.sqrt(np.einsum("tjc,tjc->tj", vec, vec)), 1e-6)
    if not whole:
        scale *= seen
    out: FloatArray = pos[:, :1] + np.matmul(PATH, vec * scale[..., None])
    if not whole:
        out *= seen[..., None]
    return out, seen


def normalize_bones(frames: FloatArray) -> FloatArray:
    """Rescale every segment to its standard length, keeping directions; NaN stays NaN."""
    out, seen = _bones(frames)
    out[~seen] = np.nan
    return out


# Real cameras look down 10-30 deg: a trunk tilted further from the camera's vertical than
# this is the person's doing (lying, bending), kept rather than levelled away.
MAX_TILT = 0.6
_TRUNK = (J["SpineShoulder"], J["Neck"], J["SpineMid"])


def _up(frame: FloatArray, origin: FloatArray) -> FloatArray:
    """The body's vertical: the trunk's direction, tilted from the camera's vertical by
    :data:`MAX_TILT` at most (the camera's vertical when no trunk joint is seen)."""
    vertical = np.array([0.0, 1.0, 0.0])
    for joint in _TRUNK:
        trunk = frame[joint] - origin
        norm = float(np.linalg.norm(trunk))
        if np.isnan(trunk).any() or norm < 1e-6:
            continue
        trunk = np.asarray(trunk / norm, dtype=np.float64)
        tilt = float(np.arccos(np.clip(trunk[1], -1.0, 1.0)))
        if tilt <= MAX_TILT:
            return trunk
        side = trunk - trunk[1] * vertical
        side /= max(float(np.linalg.norm(side)), 1e-9)
        out: FloatArray = np.cos(MAX_TILT) * vertical + np.sin(MAX_TILT) * side
        return out
    return vertical


@dataclass(frozen=True)
class ViewFrame:
    """A body-centred frame: origin at the root, the body's left-right axis along x."""

    origin: FloatArray
    rotation: FloatArray

    @staticmethod
    def of(frame: FloatArray) -> ViewFrame:
        """The view frame of one (bone-normalised) skeleton: up along its trunk (which
        removes the camera's pitch), x along its hips and shoulders (the camera's
        heading), the origin at its root (the camera's height and distance)."""
        origin = frame[J["SpineBase"]]
        if np.isnan(origin).any():
            seen = frame[visible(frame[None])[0]]
            origin = seen.mean(axis=0) if len(seen) else np.zeros(3)
        up = _up(frame, origin)
        # The body's left-right axis from shoulders and hips together: a lifted hip often
        # takes the depth of the hand or thigh in front of it, and the 0.34 m shoulder
        # baseline outweighs the 0.16 m hip one.
        across = np.zeros(3)
        for left, right in (("HipLeft", "HipRight"), ("ShoulderLeft", "ShoulderRight")):
            pair = frame[J[right]] - frame[J[left]]
            if not np.isnan(pair).any():
                across += pair
        across -= (across @ up) * up
        norm = float(np.linalg.norm(across))
        if norm < 1e-6:  # no pair seen: keep the camera's heading
            across = np.array([1.0, 0.0, 0.0]) - up[0] * up
            norm = float(np.linalg.norm(across))
        x = across / norm
        rotation = np.stack([x, up, np.cross(x, up)])
        return ViewFrame(np.asarray(origin, dtype=np.float64), rotation)

    @staticmethod
    def of_bones(pos: FloatArray, seen: BoolArray) -> ViewFrame:
        """The view frame of one frame of :func:`_bones` output."""
        return ViewFrame.of(np.where(seen[:, None], pos, np.nan))

    def apply(self, frames: FloatArray) -> FloatArray:
        out: FloatArray = (frames - self.origin) @ self.rotation.T
        return out


def _features(coords: FloatArray, seen: BoolArray) -> npt.NDArray[np.float32]:
    """Model input ``(..., frames, 100)``: coordinates (0 where unseen) and seen flags."""
    out = np.empty((*seen.shape[:-1], FEATURES_PER_FRAME), np.float32)
    out[..., : NUM_JOINTS * 3] = (coords * seen[..., None]).reshape(*seen.shape[:-1], -1)
    out[..., NUM_JOINTS * 3 :] = seen
    return out


def preprocess(frames: FloatArray) -> npt.NDArray[np.float32]:
    """A raw skeleton sequence to model features, the view taken from its first frame."""
    pos, seen = _bones(frames)
    return _features(ViewFrame.of_bones(pos[0], seen[0]).apply(pos), seen)


def preprocess_batch(frames: FloatArray) -> npt.NDArray[np.float32]:
    """:func:`preprocess` over ``(batch, frames, 25, 3)``, in one pass over all frames."""
    b, t = frames.shape[:2]
    pos, seen = _bones(frames.reshape(b * t, *frames.shape[2:]))
    pos, seen = pos.reshape(b, t, NUM_JOINTS, 3), seen.reshape(b, t, NUM_JOINTS)
    views = [ViewFrame.of_bones(pos[i, 0], seen[i, 0]) for i in range(b)]
    origins = np.stack([v.origin for v in views])[:, None, :]
    rotations = np.stack([v.rotation.T for v in views])
    coords = np.matmul(pos.reshape(b, t * NUM_JOINTS, 3) - origins, rotations)
    return _features(coords.reshape(pos.shape), seen)


def view_features(view: ViewFrame, frames: FloatArray) -> npt.NDArray[np.float32]:
    """Features of raw frames in a fixed view (streaming: the view of the first frame)."""
    pos, seen = _bones(frames)
    return _features(view.apply(pos), seen)


def first_view(frame: FloatArray) -> ViewFrame:
    """The view frame of a raw frame, bones normalised first."""
    pos, seen = _bones(frame[None])
    return ViewFrame.of_bones(pos[0], seen[0])
