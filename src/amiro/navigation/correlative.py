"""Correlative scan matching: exhaustive search of a pose window, coarse grid first.

Gauss-Newton only finds the nearest local optimum; closing a loop after metres of drift
needs the global optimum of a wide window (Olson 2009, "Real-time correlative scan
matching").  Every rotation step and every translation on a coarse lattice is scored on a
max-pooled map (an optimistic estimate of the fine scores it covers), the best few distinct
candidates are searched again at full resolution, and the runner-up's score is reported so
the caller can reject ambiguous matches (a corridor looks the same a door further on).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from scipy.ndimage import gaussian_filter, maximum_filter

from amiro.core.geometry import wrap_angle
from amiro.core.messages import Pose2D
from amiro.navigation.scan_kernels import lattice_cells, score_lattice

FloatArray = npt.NDArray[np.float64]


# a window wider than this many coarse cells each side (6 m) is searched with one more
# level; narrower ones exhaustively: the wide level prunes to its best cells, and in
# cluttered offices that loses the true match (Seattle, Pepper drift: ATE 0.19 -> 1.14 m)
WIDE_CELLS = 30
# the wide level's best distinct poses that are searched again on the coarse lattice
WIDE_BRANCHES = 8


@dataclass(frozen=True)
class ScanMatch:
    pose: Pose2D
    score: float  # mean hit likelihood of the scan points in seen space, 0..1
    runner_up: float  # best score of a pose at least ``separation`` away


@dataclass(frozen=True)
class SearchWindow:
    xy: float  # half-width, metres
    theta: float  # half-width, radians


class CorrelativeMatcher:
    """Matches scans against one occupancy-probability grid (lower-left corner ``origin``)."""

    def __init__(
        self,
        prob: npt.NDArray[np.float32],
        resolution: float,
        origin: tuple[float, float],
        coarse_factor: int = 4,
        angle_step: float = math.radians(1.0),
        separation: float = 1.0,
        min_known: float = 0.5,
        wide_factor: int = 4,
    ) -> None:
        hits = np.clip(2.0 * (prob.astype(np.float64) - 0.5), 0.0, 1.0)  # unknown, free: 0
        # a one-cell blur tolerates sub-cell error; x2.5 brings a thin wall's peak back to ~1
        fine = np.asarray(gaussian_filter(hits, 1.0) * 2.5).clip(0.0, 1.0)
        # points in unseen space say nothing either way: the score averages over the points
        # that land in seen cells, else a match would slide to cover the map more fully
        known = maximum_filter((prob != 0.5).astype(np.float64), size=3)
        size = coarse_factor + 1
        coarse = maximum_filter(fine, size=size, mode="constant")
        known_coarse = maximum_filter(known, size=size, mode="constant")
        self.fine = (fine.astype(np.float32), known.astype(np.float32))
        self.coarse = (coarse.astype(np.float32), known_coarse.astype(np.float32))
        self.wide_factor = wide_factor
        self._wide: tuple[npt.NDArray[np.float32], npt.NDArray[np.float32]] | None = None
        self.min_known = min_known
        self.resolution = resolution
        self.origin = origin
        self.factor = coarse_factor
        self.angle_step = angle_step
        self.separation = separation

    def match(
        self, px: FloatArray, py: FloatArray, guess: Pose2D, window: SearchWindow
    ) -> ScanMatch:
        """The best pose within ``window`` of ``guess`` for points (px, py) in the robot frame."""
        n_theta = max(0, math.ceil(window.theta / self.angle_step))
        thetas: FloatArray = guess.theta + self.angle_step * np.arange(-n_theta, n_theta + 1.0)
        n_xy = max(1, math.ceil(window.xy / (self.factor * self.resolution)))
        if n_xy > WIDE_CELLS:
            candidates = self._wide_candidates(px, py, guess, thetas, n_xy)
        else:
            offsets = self.factor * np.arange(-n_xy, n_xy + 1)
            scores = self._scores(self.coarse, px, py, guess.x, guess.y, thetas, offsets)
            candidates = [p for _, p in self._distinct_best(scores, thetas, offsets, guess, 4)]
        fine_offsets = np.arange(-self.factor, self.factor + 1)
        fine_steps = np.linspace(-self.angle_step, self.angle_step, 5)
        refined: list[tuple[float, Pose2D]] = []
        for cand in candidates:
            ths = cand.theta + fine_steps
            sc = self._scores(self.fine, px, py, cand.x, cand.y, ths, fine_offsets)
            k, r, c = np.unravel_index(int(np.argmax(sc)), sc.shape)
            res = self.resolution
            pose = Pose2D(
                cand.x + fine_offsets[c] * res,
                cand.y + fine_offsets[r] * res,
                wrap_angle(float(ths[k])),
            )
            refined.append((float(sc[k, r, c]), pose))
        refined.sort(key=lambda t: -t[0])
        best_score, best = refined[0]
        others = [s for s, p in refined[1:] if p.distance_to(best) >= self.separation]
        return ScanMatch(best, best_score, max(others, default=0.0))

    def _wide_level(self) -> tuple[npt.NDArray[np.float32], npt.NDArray[np.float32]]:
        """A third, wider level for windows of many metres (big loops), max-pooled again
        from the coarse one; built the first time a wide window needs it."""
        if self._wide is None:
            # the coarse level pools factor + 1 cells; together: factor * wide_factor + 1
            size = self.factor * (self.wide_factor - 1) + 1
            hit, known = self.coarse
            self._wide = (
                maximum_filter(hit, size=size, mode="constant"),
                maximum_filter(known, size=size, mode="constant"),
            )
        return self._wide

    def _wide_candidates(
        self, px: FloatArray, py: FloatArray, guess: Pose2D, thetas: FloatArray, n_xy: int
    ) -> list[Pose2D]:
        """Branch by one more level: the best distinct poses on a lattice ``wide_factor``
        coarser (scored on a map max-pooled to match, so no better pose hides under a
        cell), each searched again on the coarse lattice around it, every second rotation
        of the wide level's best +-2 steps; the best distinct poses of all of those."""
        step = self.factor * self.wide_factor
        n_wide = math.ceil(n_xy / self.wide_factor)
        offsets = step * np.arange(-n_wide, n_wide + 1)
        sub = thetas[::2] if thetas.size > 8 else thetas
        wide = self._scores(self._wide_level(), px, py, guess.x, guess.y, sub, offsets)
        near = self.factor * np.arange(-self.wide_factor, self.wide_factor + 1)
        found: list[tuple[float, Pose2D]] = []
        for _, cand in self._distinct_best(wide, sub, offsets, guess, count=WIDE_BRANCHES):
            ths = cand.theta + self.angle_step * np.arange(-2.0, 3.0)
            sc = self._scores(self.coarse, px, py, cand.x, cand.y, ths, near)
            found.extend(self._distinct_best(sc, ths, near, cand, count=2))
        found.sort(key=lambda t: -t[0])
        # the wide cells overhang the window: what lies beyond it was not asked for
        reach = n_xy * self.factor * self.resolution
        chosen: list[Pose2D] = []
        for _, p in found:
            if max(abs(p.x - guess.x), abs(p.y - guess.y)) > reach:
                continue
            if all(p.distance_to(q) >= self.separation for q in chosen):
                chosen.append(p)
            if len(chosen) == 4:
                break
        return chosen or [guess]

    def _scores(
        self,
        grids: tuple[npt.NDArray[np.float32], npt.NDArray[np.float32]],
        px: FloatArray,
        py: FloatArray,
        x: float,
        y: float,
        thetas: FloatArray,
        offsets: npt.NDArray[np.int64],
    ) -> FloatArray:
        """Mean grid value at the points in seen cells (at least ``min_known`` of them) for
        every (theta, row offset, column offset)."""
        rows, cols = lattice_cells(px, py, x, y, thetas, self.origin, self.resolution)
        hit, known = grids
        return score_lattice(
            hit, known, rows, cols, offsets.astype(np.int64), self.min_known * len(px)
        )

    def _distinct_best(
        self,
        scores: FloatArray,
        thetas: FloatArray,
        offsets: npt.NDArray[np.int64],
        centre: Pose2D,
        count: int,
    ) -> list[tuple[float, Pose2D]]:
        """The best-scoring lattice poses around ``centre`` with their scores, each at least
        ``separation`` from the others (greedy non-maximum suppression over the best
        rotation per translation)."""
        best_theta = np.argmax(scores, axis=0)
        plane = np.max(scores, axis=0)
        metres = offsets * self.resolution
        dy, dx = np.meshgrid(metres, metres, indexing="ij")
        chosen: list[tuple[float, Pose2D]] = []
        while len(chosen) < count and np.isfinite(plane).any():
            r, c = np.unravel_index(int(np.argmax(plane)), plane.shape)
            pose = Pose2D(centre.x + dx[r, c], centre.y + dy[r, c], float(thetas[best_theta[r, c]]))
            chosen.append((float(plane[r, c]), pose))
            plane[np.hypot(dx - dx[r, c], dy - dy[r, c]) < self.separation] = -np.inf
        return chosen
