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

from amiro.core.messages import Pose2D
from amiro.navigation.correlative import CorrelativeMatcher, SearchWindow
from amiro.navigation.poses import between, compose
from amiro.navigation.slam import match_scan
from amiro.navigation.submaps import Submap

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class LoopParams:
    min_travel_m: float = 20.0
    window_base_m: float = 0.5
    window_per_m: float = 0.03  # search half-width per metre travelled since the last closure
    window_max_m: float = 6.0
    theta_base: float = math.radians(3.0)
    theta_per_m: float = math.radians(0.1)
    theta_max: float = math.radians(15.0)
    min_score: float = 0.5
    max_ambiguity: float = 0.9  # runner-up score / best score
    max_candidates: int = 2
    max_range: float = 12.0


@dataclass(frozen=True)
class LoopEdge:
    anchor: int  # keyframe the submap hangs on
    z: Pose2D  # the current keyframe seen from the anchor
    score: float
    runner_up: float


@dataclass
class _Finished:
    submap: Submap
    matcher: CorrelativeMatcher
    travel: float  # path length when finished


class LoopCloser:
    def __init__(self, params: LoopParams | None = None) -> None:
        self.params = params or LoopParams()
        self._submaps: list[_Finished] = []
        self.rejected = 0

    def add(self, submap: Submap, travel: float) -> None:
        fine = submap.levels[0]
        matcher = CorrelativeMatcher(fine.prob, fine.resolution, fine.origin)
        self._submaps.append(_Finished(submap, matcher, travel))

    def search(
        self,
        px: FloatArray,
        py: FloatArray,
        current: Pose2D,
        anchor_pose: list[Pose2D],
        travel: float,
        since_closure: float,
    ) -> list[LoopEdge]:
        """Loop edges for a keyframe at graph pose ``current`` (``anchor_pose[k]``: graph
        pose of keyframe k)."""
        p = self.params
        window = SearchWindow(
            min(p.window_max_m, p.window_base_m + p.window_per_m * since_closure),
            min(p.theta_max, p.theta_base + p.theta_per_m * since_closure),
        )
        reach = p.max_range + window.xy
        near = []
        for fin in self._submaps:
            if fin.travel > travel - p.min_travel_m:
                continue
            g_anchor = anchor_pose[fin.submap.anchor]
            d = g_anchor.distance_to(current)
            if d < reach + fin.submap.travel:
                near.append((d, fin, g_anchor))
        near.sort(key=lambda t: t[0])
        edges = []
        for _, fin, g_anchor in near[: p.max_candidates]:
            sm = fin.submap
            guess = compose(sm.anchor_pose, between(g_anchor, current))
            found = fin.matcher.match(px, py, guess, window)
            if found.score < p.min_score or found.runner_up > p.max_ambiguity * found.score:
                self.rejected += 1
                continue
            refined = match_scan(sm.levels, px, py, found.pose, 0.0, 6)
            if refined.distance_to(found.pose) > 0.2:
                refined = found.pose
            edges.append(
                LoopEdge(sm.anchor, between(sm.anchor_pose, refined), found.score, found.runner_up)
            )
        return edges
