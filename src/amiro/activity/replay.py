"""Recorded real motion for the simulated residents: real skeleton files in a folder the
user names, by amiro activity, in the residents' body frame.

The simulator's residents otherwise perform the synthetic motion the model was trained
on, which flatters the model.  Read from the folder (recursively):

- NTU RGB+D ``.skeleton`` files, the activity from the name's action id (``A001`` drink
  water, ...; see :data:`~amiro.activity.labels.NTU_ACTION_IDS`), 30 Hz taken to 15 Hz;
- the real Kinect v1 sets in their published layouts (``kard/``, ``florence3d/``,
  ``cad60/``, ``citi_dailyactivities3d/``: :mod:`amiro.activity.real_sets`).

Each clip is turned into the body frame (x to the person's right, y up from the floor, z
behind them, the pelvis over the origin): its first frame's trunk gives the vertical (the
recording camera's pitch removed), its shoulders and hips the heading, its lowest foot the
floor.  Clips of actions amiro does not know are not used.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from amiro.activity.labels import NTU_ACTION_IDS
from amiro.activity.normalize import ViewFrame
from amiro.activity.ntu import action_id, read_skeleton_file
from amiro.activity.real_sets import READERS, load
from amiro.activity.skeleton import FloatArray, J
from amiro.core.config import ConfigError

FEET = tuple(J[n] for n in ("FootLeft", "FootRight", "AnkleLeft", "AnkleRight"))
PELVIS_HEIGHT_M = 0.95  # the floor's guess when no foot is ever seen
MIN_FRAMES = 8


def body_frame(frames: FloatArray) -> FloatArray:
    """A clip in camera space (Kinect axes) in the body frame of its first frame."""
    view = ViewFrame.of(frames[0])
    out = view.apply(frames)
    feet = out[:, FEET, 1]
    floor = float(np.nanmin(feet)) if np.isfinite(feet).any() else -PELVIS_HEIGHT_M
    out[..., 1] -= floor
    return out


def load_motion(folder: Path) -> dict[str, list[FloatArray]]:
    """Every usable real clip under ``folder`` by amiro activity, in the body frame."""
    if not folder.is_dir():
        raise ConfigError(f"sim.skeletons.replay: {folder}: no such folder")
    by_id = {ntu: name for name, ntu in NTU_ACTION_IDS.items()}
    clips: list[tuple[str | None, FloatArray]] = []
    for path in sorted(folder.rglob("*.skeleton")):
        action = action_id(path)
        if action not in by_id:
            continue
        try:
            body = read_skeleton_file(path).main_body()
        except ConfigError:
            continue
        clips.append((by_id[action], body.joints[body.present][::2]))
    sets = tuple(name for name, (rel, _) in READERS.items() if (folder / rel).exists())
    clips.extend((c.label, c.frames) for c in load(folder, sets))
    motion: dict[str, list[FloatArray]] = {}
    for label, frames in clips:
        if label is not None and len(frames) >= MIN_FRAMES:
            motion.setdefault(label, []).append(body_frame(frames))
    if not motion:
        raise ConfigError(
            f"sim.skeletons.replay: {folder}: no skeleton file of an amiro activity "
            "(NTU .skeleton files, or the kard/, florence3d/, cad60/, citi sets)"
        )
    return motion
