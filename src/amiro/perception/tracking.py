"""People tracks in the map frame: stable ids, smoothed positions, fused identities.

A face is recognised only now and then (it turns away, it is backlit); a track keeps the
name once recognised, so the person stays known while only the body is detected.  A track
is confirmed after two hits or a recognised face, which filters one-frame false positives.
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass, field

from amiro.core.messages import Point
from amiro.perception.config import TrackingSection


@dataclass(frozen=True, slots=True)
class Measurement:
    position: Point
    score: float
    name: str | None = None
    face_backlit: bool = False


@dataclass
class Track:
    id: str
    position: Point
    score: float
    last_seen: float
    hits: int = 1
    face_backlit: bool = False
    votes: Counter[str] = field(default_factory=Counter)

    @property
    def name(self) -> str | None:
        ranked = [*self.votes.most_common(2), ("", 0), ("", 0)]
        return ranked[0][0] if ranked[0][1] > ranked[1][1] else None

    @property
    def confirmed(self) -> bool:
        return self.hits >= 2 or self.name is not None


def _distance(a: Point, b: Point) -> float:
    return math.hypot(a.x - b.x, a.y - b.y)


class PeopleTracker:
    """Greedy nearest-neighbour association within a gate, exponential smoothing."""

    def __init__(self, cfg: TrackingSection | None = None) -> None:
        self.cfg = cfg or TrackingSection()
        self.tracks: list[Track] = []
        self._next_id = 1

    def _merge_duplicates(self, found: list[Measurement]) -> list[Measurement]:
        """Two boxes on one person (a detector duplicate) become one measurement."""
        kept: list[Measurement] = []
        for m in sorted(found, key=lambda m: (m.name is None, -m.score)):
            if all(_distance(m.position, k.position) > self.cfg.gate_m / 2 for k in kept):
                kept.append(m)
        return kept

    def update(self, now: float, found: list[Measurement]) -> list[Track]:
        """Fold this frame's measurements in; returns the tracks updated now."""
        self.tracks = [t for t in self.tracks if now - t.last_seen <= self.cfg.forget_s]
        measurements = self._merge_duplicates(found)
        pairs = sorted(
            (_distance(t.position, m.position), ti, mi)
            for ti, t in enumerate(self.tracks)
            for mi, m in enumerate(measurements)
        )
        used_t: set[int] = set()
        used_m: set[int] = set()
        updated: list[Track] = []
        for dist, ti, mi in pairs:
            if dist > self.cfg.gate_m or ti in used_t or mi in used_m:
                continue
            used_t.add(ti)
            used_m.add(mi)
            updated.append(self._fold(self.tracks[ti], measurements[mi], now))
        for mi, m in enumerate(measurements):
            if mi not in used_m:
                track = Track(f"person_{self._next_id}", m.position, m.score, now)
                self._next_id += 1
                self._vote(track, m)
                self.tracks.append(track)
                updated.append(track)
        return updated

    def _fold(self, track: Track, m: Measurement, now: float) -> Track:
        a = self.cfg.smoothing
        p, q = track.position, m.position
        track.position = Point(p.x + a * (q.x - p.x), p.y + a * (q.y - p.y), p.z + a * (q.z - p.z))
        track.score = max(track.score, m.score)
        track.last_seen = now
        track.hits += 1
        self._vote(track, m)
        return track

    @staticmethod
    def _vote(track: Track, m: Measurement) -> None:
        track.face_backlit = m.face_backlit and m.name is None
        if m.name is not None:
            track.votes[m.name] += 1
