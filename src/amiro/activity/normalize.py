"""Skeleton preprocessing: bone lengths to the standard body, view to facing the camera.

Bone normalisation removes the subject's size (section 3.5); view normalisation removes
where the camera stood, so one model serves every robot height and viewing angle.  Both
work with missing joints: a joint whose parent is missing hangs from its nearest seen
ancestor, at the standard length of the path between them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from amiro.activity.skeleton import (
    DEPTH,
    NUM_JOINTS,
    PARENT,
    PATH,
    ROOT_DISTANCE,
    FloatArray,
    J,
    visible,
)

# ANCESTOR_RANK[j, k] = depth(k) + 1 when k is a strict ancestor of j: the deepest seen
# ancestor of j is then an argmax.
ANCESTOR_RANK = np.zeros((NUM_JOINTS, NUM_JOINTS))
for _j in range(1, NUM_JOINTS):
    _k = PARENT[_j]
    while _k >= 0:
        ANCESTOR_RANK[_j, _k] = DEPTH[_k] + 1
        _k = PARENT[_k]

FEATURES_PER_FRAME = NUM_JOINTS * 4  # 3 coordinates and a seen flag per joint


def normalize_bones(frames: FloatArray) -> FloatArray:
    """Rescale every segment to its standard length, keeping directions; NaN stays NaN."""
    seen = visible(frames)
    pos = np.nan_to_num(frames)
    counts = seen.sum(axis=1)
    no_root = ~seen[:, 0] & (counts > 0)
    if no_root.any():  # the root stands in at the centroid of what was seen
        centroid = (pos * seen[..., None]).sum(axis=1) / np.maximum(counts, 1)[:, None]
        pos[no_root, 0] = centroid[no_root]
    anchors_ok = seen.copy()
    anchors_ok[:, 0] = True
    anchor = (anchors_ok[:, None, :] * ANCESTOR_RANK[None]).argmax(axis=-1)
    anchor_pos = np.take_along_axis(pos, anchor[..., None], axis=1)
    vec = pos - anchor_pos
    length = np.linalg.norm(vec, axis=-1)
    target = ROOT_DISTANCE[None, :] - ROOT_DISTANCE[anchor]
    scale = np.where(seen, target / np.maximum(length, 1e-6), 0.0)
    scale[:, 0] = 0.0
    out: FloatArray = pos[:, :1] + np.einsum("jk,tkc->tjc", PATH, vec * scale[..., None])
    out[~seen] = np.nan
    return out


@dataclass(frozen=True)
class ViewFrame:
    """A body-centred frame: origin at the root, the body's left-right axis along x."""

    origin: FloatArray
    rotation: FloatArray

    @staticmethod
    def of(frame: FloatArray) -> ViewFrame:
        """The view frame of one (bone-normalised) skeleton, from its hips or shoulders."""
        origin = frame[J["SpineBase"]]
        if np.isnan(origin).any():
            seen = frame[visible(frame[None])[0]]
            origin = seen.mean(axis=0) if len(seen) else np.zeros(3)
        yaw = 0.0
        for left, right in (("HipLeft", "HipRight"), ("ShoulderLeft", "ShoulderRight")):
            across = frame[J[right]] - frame[J[left]]
            if not np.isnan(across).any() and np.hypot(across[0], across[2]) > 1e-6:
                yaw = float(np.arctan2(across[2], across[0]))
                break
        c, s = np.cos(yaw), np.sin(yaw)
        # Rotation about the vertical (y) axis taking the across vector onto +x.
        rotation = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
        return ViewFrame(np.asarray(origin, dtype=np.float64), rotation)

    def apply(self, frames: FloatArray) -> FloatArray:
        out: FloatArray = (frames - self.origin) @ self.rotation.T
        return out


def features(normalised: FloatArray) -> np.ndarray:
    """Model input per frame: coordinates (0 where unseen) and the seen flags, float32."""
    seen = visible(normalised)
    coords = np.nan_to_num(normalised).reshape(len(normalised), -1)
    return np.concatenate([coords, seen], axis=1).astype(np.float32)


def preprocess(frames: FloatArray) -> np.ndarray:
    """A raw skeleton sequence to model features, the view taken from its first frame."""
    bones = normalize_bones(frames)
    return features(ViewFrame.of(bones[0]).apply(bones))


def preprocess_batch(frames: FloatArray) -> np.ndarray:
    """:func:`preprocess` over ``(batch, frames, 25, 3)``, bones normalised in one pass."""
    b, t = frames.shape[:2]
    bones = normalize_bones(frames.reshape(b * t, *frames.shape[2:])).reshape(frames.shape)
    return np.stack([features(ViewFrame.of(seq[0]).apply(seq)) for seq in bones])
