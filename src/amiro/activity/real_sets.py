"""Readers for the real Kinect v1 skeleton sets: KARD, Florence 3D, CAD-60, CITI.

Each clip comes out as NTU-25 frames in Kinect camera space (metres, x to the sensor's
left, y up, z away) at the model's rate, with its set, subject, source action and the
amiro class it shows, or None for any other action (a real "unknown").  The files are
research data read from where the user keeps them (``../shared/data/har`` here); nothing
of them ships with amiro.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from amiro.activity.augment import mirror
from amiro.activity.kinect_v1 import resample_rate, to_ntu
from amiro.activity.motion import FPS
from amiro.activity.skeleton import FloatArray
from amiro.core.config import ConfigError

MM = 1e-3

# Source action id -> amiro class, for the actions that are one of amiro's; every other
# action of a set is an "unknown" example.  A phone call is the real sets' phone action.
KARD_CLASSES = {1: "hand_waving", 2: "hand_waving", 3: "hand_waving", 15: "play_phone",
                16: "drink_water", 18: "standing_up"}  # fmt: skip
FLORENCE_CLASSES = {1: "hand_waving", 2: "drink_water", 3: "play_phone", 7: "standing_up"}
CAD60_CLASSES = {2: "play_phone", 4: "drink_water", 16: "typing"}
CITI_CLASSES = {5: "standing_up", 12: "play_phone", 13: "drink_water", 14: "hand_waving"}

# Recording rates: Kinect v1 at 30 Hz; Florence's files keep about one frame in three of
# its 30 Hz videos (a 2-3 s action in a median 17 frames); CITI resampled every sequence
# to 100 frames, taken as its typical 3.3 s at 30 Hz.
RATES = {"kard": 30.0, "florence3d": 10.0, "cad60": 30.0, "citi": 30.0}
SETS = tuple(RATES)
# KARD's x points to the sensor's right (its right shoulders lie on the sensor's left).
AXES = {"kard": (-1.0, 1.0, 1.0)}
# CAD-60's NITE skeletons are mirror images (three of its four people drink and phone
# with the "left" hand, which also lies on the left): mirrored back.
MIRRORED = frozenset({"cad60"})


@dataclass(frozen=True)
class Clip:
    dataset: str
    subject: int
    action: int  # the set's own action id
    label: str | None  # amiro's class, None for an action amiro does not know
    frames: FloatArray  # (T, 25, 3) at the model's rate


def _clip(
    dataset: str, subject: int, action: int, raw: FloatArray, classes: dict[int, str]
) -> Clip:
    scale = np.asarray(AXES.get(dataset, (1.0, 1.0, 1.0))) * (1.0 if dataset == "citi" else MM)
    frames = resample_rate(to_ntu(raw * scale, dataset).frames, RATES[dataset], FPS)
    if dataset in MIRRORED:
        frames = mirror(frames)
    return Clip(dataset, subject, action, classes.get(action), frames)


def _text_frames(path: Path, joints: int) -> FloatArray:
    values = np.loadtxt(path, usecols=(0, 1, 2), ndmin=2)
    whole = len(values) // joints * joints
    out: FloatArray = values[:whole].reshape(-1, joints, 3)
    return out


def read_kard(folder: Path) -> list[Clip]:
    """``aAA_sSS_eEE_realworld.txt``: 15 joints per frame, ``x y z`` mm."""
    clips = []
    for path in sorted(folder.glob("a*_s*_e*_realworld.txt")):
        action, subject = (int(p[1:]) for p in path.stem.split("_")[:2])
        clips.append(_clip("kard", subject, action, _text_frames(path, 15), KARD_CLASSES))
    return clips


def read_florence(folder: Path) -> list[Clip]:
    """``aAA_sS_idN.txt``: 15 joints per frame, ``x y z`` mm."""
    clips = []
    for path in sorted(folder.glob("a*_s*_id*.txt")):
        action, subject = (int(p[1:]) for p in path.stem.split("_")[:2])
        raw = _text_frames(path, 15)
        clips.append(_clip("florence3d", subject, action, raw, FLORENCE_CLASSES))
    return clips


def read_cad60(npz: Path) -> list[Clip]:
    """The positions archive: ~1 s segments, joined back into one clip per person and
    activity in segment order (CAD-60 records each activity as one continuous take)."""
    data = np.load(npz)
    frames, start, length = data["frames"], data["seg_start"], data["seg_len"]
    label, person, index = data["label"], data["person"], data["segment_index"]
    clips = []
    for action, subject in sorted({(int(a), int(p)) for a, p in zip(label, person, strict=True)}):
        segs = np.flatnonzero((label == action) & (person == subject))
        segs = segs[np.argsort(index[segs], kind="stable")]
        raw = np.concatenate([frames[start[s] : start[s] + length[s]] for s in segs])
        clips.append(_clip("cad60", subject, action, raw.astype(np.float64), CAD60_CLASSES))
    return clips


def read_citi(folder: Path) -> list[Clip]:
    """``citi_data/*.npy`` (100, 57) body-centred metres, third coordinate up; labels in
    ``citi_labels``.  Turned into Kinect axes (x, up, y): its second axis points away
    from the sensor (drinking hands come out in front of the body only so)."""
    labels = folder / "citi_labels"
    actions = np.load(labels / "action_labels.npy").ravel()
    subjects = np.load(labels / "subject_labels.npy").ravel()
    clips = []
    for i, (action, subject) in enumerate(zip(actions, subjects, strict=True)):
        seq = np.load(folder / "citi_data" / f"citi_data_{i + 1:04d}.npy").reshape(-1, 19, 3)
        kinect = np.stack([seq[..., 0], seq[..., 2], seq[..., 1]], axis=-1)
        clips.append(_clip("citi", int(subject), int(action), kinect, CITI_CLASSES))
    return clips


READERS: dict[str, tuple[str, Callable[[Path], list[Clip]]]] = {
    "kard": ("kard/kard_realworld", read_kard),
    "florence3d": ("florence3d/florence", read_florence),
    "cad60": ("cad60/cad60_positions_all_classes.npz", read_cad60),
    "citi": ("citi_dailyactivities3d", read_citi),
}


def load(root: Path, sets: tuple[str, ...] = SETS, progress: bool = False) -> list[Clip]:
    """Every clip of ``sets`` under ``root`` (the folder holding ``kard/``, ...)."""
    clips = []
    for name in sets:
        if name not in READERS:
            raise ConfigError(f"unknown skeleton set {name!r}; known: {', '.join(READERS)}")
        rel, reader = READERS[name]
        path = root / rel
        if not path.exists():
            raise ConfigError(f"{path}: no such file or folder (the {name} set)")
        if progress:
            print(f"reading {name} from {path}", file=sys.stderr)
        clips.extend(reader(path))
    return clips


# Who trains, who picks the threshold, who tests.  Florence 3D is never trained on: the
# cross-dataset test.  Within the other sets whole subjects are held out (cross-subject);
# CITI's subject 11 holds the sequences with outlier frames and trains.
ROLES: dict[str, dict[str, frozenset[int]]] = {
    "kard": {
        "train": frozenset(range(1, 7)),
        "validation": frozenset({7}),
        "test": frozenset({8, 9, 10}),
    },
    "cad60": {"train": frozenset({1, 2}), "validation": frozenset({3}), "test": frozenset({4})},
    "citi": {
        "train": frozenset({1, 2, 3, 4, 5, 6, 11}),
        "validation": frozenset({7}),
        "test": frozenset({8, 9, 10}),
    },
    "florence3d": {
        "train": frozenset(),
        "validation": frozenset(),
        "test": frozenset(range(1, 11)),
    },
}


def role(clip: Clip) -> str:
    """``train``, ``validation`` or ``test``: where a clip serves."""
    for name, subjects in ROLES[clip.dataset].items():
        if clip.subject in subjects:
            return name
    return "test"
