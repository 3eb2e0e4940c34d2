"""Loop-closure detection: match the current keyframe's scan against older submaps nearby.

Candidates are the finished submaps (at least ``min_travel_m`` back along the path) whose
anchors lie within sensor reach of the current pose estimate.  The search window grows with
the distance travelled since the last closure, since that is how far the estimate can have
drifted.  A match is kept only if it is good (``min_score``) and unique (the best distinct
alternative scores at most ``max_ambiguity`` of it); it is refined with Gauss-Newton and
becomes a relative-pose edge between the submap's anchor keyframe and the current one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from amiro.core.geometry import wrap_angle
from amiro.core.messages import Pose2D
from amiro.navigation.correlative import CorrelativeMatcher, SearchWindow
from amiro.navigation.poses import between, compose
from amiro.navigation.slam import match_scan
from amiro.navigation.submaps import Submap

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class LoopParams:
    min_travel_m: float = 20.0
    window_base_m: float = 2.0  # wide enough to see aliases, for the uniqueness test
    window_per_m: float = 0.02  # search half-width per metre travelled since the last closure
    window_max_m: float = 16.0
    theta_base: float = math.radians(3.0)
    theta_per_m: float = math.radians(0.1)
    theta_max: float = math.radians(15.0)
    min_score: float = 0.5
    max_ambiguity: float = 0.85  # runner-up score / best score
    max_candidates: int = 2
    far_m: float = 60.0  # a submap this much travel back has drifted with the whole path
    span_margin_m: float = 1.0
    agree_m: float = 0.3  # two matches agree if their corrections differ less than this
    agree_rad: float = math.radians(2.0)
    consensus_m: float = 8.0  # how far back a match waits for a second one that agrees
    independent_m: float = 3.0  # agreeing matches must come from this far apart
    witnesses: int = 2  # earlier matches that must agree with a new one to correct the map
    # ... unless it is this unique (runner-up / best): the first closure of a big loop,
    # after metres of drift, seldom finds a second witness before the robot has passed
    unique_ratio: float = 0.65


@dataclass(frozen=True)
class LoopEdge:
    anchor: int  # keyframe the submap hangs on
    keyframe: int
    z: Pose2D  # ``keyframe`` seen from ``anchor``
    score: float
    runner_up: float


@dataclass(frozen=True)
class _Candidate:
    edge: LoopEdge
    travel: float
    correction: tuple[float, float, float]  # implied pose minus estimate (map frame)


@dataclass
class _Finished:
    submap: Submap
    matcher: CorrelativeMatcher
    travel: float  # path length when finished


class LoopCloser:
    def __init__(self, params: LoopParams | None = None) -> None:
        self.params = params or LoopParams()
        self._submaps: list[_Finished] = []
        self._waiting: list[_Candidate] = []
        self.rejected = 0

    def add(self, submap: Submap, travel: float) -> None:
        fine = submap.levels[0]
        matcher = CorrelativeMatcher(fine.prob, fine.resolution, fine.origin)
        self._submaps.append(_Finished(submap, matcher, travel))

    def search(
        self,
        keyframe: int,
        px: FloatArray,
        py: FloatArray,
        poses: FloatArray,
        travel: float,
        since_closure: float,
    ) -> list[LoopEdge]:
        """Verified loop edges for ``keyframe`` (points px, py in its frame; ``poses``: graph
        pose of every keyframe).  A match whose correction of the current estimate is
        small is accepted at once; a larger one (a first closure after a long drift, or an
        alias along a corridor) waits until ``witnesses`` matches from other submaps and
        places imply the same correction, since aliases a few metres apart rarely agree."""
        current = _pose(poses, keyframe)
        found = self._matches(keyframe, px, py, current, poses, travel, since_closure)
        p = self.params
        self._waiting = [c for c in self._waiting if travel - c.travel <= p.consensus_m]
        accepted: list[LoopEdge] = []
        for cand in found:
            dx, dy, dth = cand.correction
            small = math.hypot(dx, dy) < p.agree_m and abs(dth) < p.agree_rad
            if small or cand.edge.runner_up <= p.unique_ratio * cand.edge.score:
                accepted.append(cand.edge)
                continue
            agreeing = [w for w in self._waiting if _agree(w, cand, p)]
            if len(agreeing) >= p.witnesses:
                accepted.extend(w.edge for w in agreeing)
                accepted.append(cand.edge)
                self._waiting = [w for w in self._waiting if w not in agreeing]
            else:
                self._waiting.append(cand)
        return accepted

    def _window(self, apart_m: float, since_closure: float) -> SearchWindow:
        """How far the estimate can have drifted from a submap built ``apart_m`` of travel
        ago: the drift of that path, unless a closure since then has bounded it (a closure
        ties the estimate to the map only near where it happened, so the two are summed
        only up to the path between them)."""
        p = self.params
        drift_m = max(since_closure, apart_m) if apart_m > p.far_m else since_closure
        return SearchWindow(
            min(p.window_max_m, p.window_base_m + p.window_per_m * drift_m),
            min(p.theta_max, p.theta_base + p.theta_per_m * drift_m),
        )

    def _matches(
        self,
        keyframe: int,
        px: FloatArray,
        py: FloatArray,
        current: Pose2D,
        poses: FloatArray,
        travel: float,
        since_closure: float,
    ) -> list[_Candidate]:
        p = self.params
        near = []
        for fin in self._submaps:
            if fin.travel > travel - p.min_travel_m:
                continue
            window = self._window(travel - fin.travel, since_closure)
            # only submaps built from around here: their scans looked where this one looks
            span = poses[fin.submap.anchor : fin.submap.last_keyframe + 1, :2]
            d = float(np.min(np.hypot(span[:, 0] - current.x, span[:, 1] - current.y)))
            if d < window.xy + p.span_margin_m:
                near.append((d, fin, window))
        near.sort(key=lambda t: t[0])
        edges = []
        for _, fin, window in near[: p.max_candidates]:
            g_anchor = _pose(poses, fin.submap.anchor)
            sm = fin.submap
            guess = compose(sm.anchor_pose, between(g_anchor, current))
            found = fin.matcher.match(px, py, guess, window)
            if found.score < p.min_score or found.runner_up > p.max_ambiguity * found.score:
                self.rejected += 1
                continue
            refined = match_scan(sm.levels, px, py, found.pose, 0.0, 6)
            if refined.distance_to(found.pose) > 0.2:
                refined = found.pose
            z = between(sm.anchor_pose, refined)
            implied = compose(g_anchor, z)
            correction = (
                implied.x - current.x,
                implied.y - current.y,
                wrap_angle(implied.theta - current.theta),
            )
            edge = LoopEdge(sm.anchor, keyframe, z, found.score, found.runner_up)
            edges.append(_Candidate(edge, travel, correction))
        return edges


def _pose(poses: FloatArray, k: int) -> Pose2D:
    x, y, th = poses[k]
    return Pose2D(float(x), float(y), float(th))


def _agree(a: _Candidate, b: _Candidate, p: LoopParams) -> bool:
    """Same correction from independent evidence: other submaps, scans metres apart (the
    same alias seen again from a step further on would agree with itself)."""
    if a.edge.anchor == b.edge.anchor or abs(a.travel - b.travel) < p.independent_m:
        return False
    (ax, ay, ath), (bx, by, bth) = a.correction, b.correction
    return math.hypot(ax - bx, ay - by) < p.agree_m and abs(wrap_angle(ath - bth)) < p.agree_rad
