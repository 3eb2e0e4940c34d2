"""NTU RGB+D ``.skeleton`` files: read and write the dataset's text format.

A file holds a frame count, then per frame a body count and per body one line of body
info (id, clipped edges, hand states, restricted, lean x/y, tracking state), a joint count
and one line per joint: x y z (camera space, m), depth x/y, colour x/y (pixels),
orientation w x y z, tracking state.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from amiro.activity.skeleton import NUM_JOINTS, FloatArray
from amiro.core.config import ConfigError

NTU_NAME = re.compile(r"S(\d{3})C(\d{3})P(\d{3})R(\d{3})A(\d{3})")


@dataclass
class Body:
    """One tracked body: its Kinect id and joints ``(frames, 25, 3)``, NaN where absent."""

    id: str
    joints: FloatArray
    present: np.ndarray  # (frames,) bool

    @property
    def frames(self) -> int:
        return int(self.present.sum())


@dataclass
class SkeletonSequence:
    frames: int
    bodies: list[Body] = field(default_factory=list)

    def main_body(self) -> Body:
        """The body tracked longest: the performer in NTU's single-person actions."""
        if not self.bodies:
            raise ConfigError("skeleton file has no body")
        return max(self.bodies, key=lambda b: b.frames)

    def summary(self) -> dict[str, Any]:
        return {
            "frames": self.frames,
            "bodies": [{"id": b.id, "frames": b.frames} for b in self.bodies],
            "joints": NUM_JOINTS,
        }


def parse_skeleton(text: str, source: str = "skeleton") -> SkeletonSequence:
    """Parse the text of a ``.skeleton`` file; malformed input raises a one-line ConfigError."""
    tokens = text.split("\n")
    pos = 0

    def line() -> list[str]:
        nonlocal pos
        while pos < len(tokens) and not tokens[pos].strip():
            pos += 1
        if pos >= len(tokens):
            raise ConfigError(f"{source}: file ends early (line {pos + 1})")
        pos += 1
        return tokens[pos - 1].split()

    def number(fields: list[str], kind: type[int] | type[float]) -> list[Any]:
        try:
            return [kind(f) for f in fields]
        except ValueError:
            raise ConfigError(f"{source}: line {pos}: not a number: {' '.join(fields)}") from None

    (n_frames,) = number(line()[:1], int)
    if n_frames < 0:
        raise ConfigError(f"{source}: negative frame count")
    found: dict[str, Body] = {}
    for f in range(n_frames):
        (n_bodies,) = number(line()[:1], int)
        for _ in range(n_bodies):
            info = line()
            if not info:
                raise ConfigError(f"{source}: line {pos}: missing body info")
            body = found.get(info[0])
            if body is None:
                body = Body(
                    info[0], np.full((n_frames, NUM_JOINTS, 3), np.nan), np.zeros(n_frames, bool)
                )
                found[info[0]] = body
            (n_joints,) = number(line()[:1], int)
            if n_joints != NUM_JOINTS:
                raise ConfigError(f"{source}: line {pos}: {n_joints} joints, expected 25")
            for j in range(n_joints):
                values = number(line(), float)
                if len(values) < 3:
                    raise ConfigError(f"{source}: line {pos}: a joint needs x y z")
                body.joints[f, j] = values[:3]
            body.present[f] = True
    return SkeletonSequence(n_frames, list(found.values()))


def read_skeleton_file(path: str | Path) -> SkeletonSequence:
    p = Path(path)
    if not p.is_file():
        raise ConfigError(f"{p}: no such file")
    try:
        text = p.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise ConfigError(f"{p}: cannot read: {exc}") from None
    return parse_skeleton(text, str(p))


def format_skeleton(seq: SkeletonSequence) -> str:
    """The ``.skeleton`` text of a sequence (fields amiro does not model are written as 0,
    joints tracked = 2 where seen, 0 and zeros where not)."""
    out = [str(seq.frames)]
    for f in range(seq.frames):
        bodies = [b for b in seq.bodies if b.present[f]]
        out.append(str(len(bodies)))
        for b in bodies:
            out.append(f"{b.id} 0 0 0 0 0 0 0 0 2")
            out.append(str(NUM_JOINTS))
            for x, y, z in b.joints[f]:
                seen = not np.isnan(x)
                xyz = f"{x:.7g} {y:.7g} {z:.7g}" if seen else "0 0 0"
                out.append(f"{xyz} 0 0 0 0 0 0 0 0 {2 if seen else 0}")
    return "\n".join(out) + "\n"


def write_skeleton_file(path: str | Path, seq: SkeletonSequence) -> None:
    Path(path).write_text(format_skeleton(seq), encoding="utf-8")


def action_id(path: str | Path) -> int | None:
    """The action number of an NTU file name (S001C002P003R002A013 -> 13)."""
    m = NTU_NAME.search(Path(path).name)
    return int(m.group(5)) if m else None
