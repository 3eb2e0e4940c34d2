"""Local submaps: the front end matches each scan to a map of the last few metres only.

A single global map goes wrong once drift has accumulated and the robot comes back: the new
scans meet walls drawn at the old, drifted poses.  So the front end (Hector matching, as in
``slam.py``) keeps two overlapping submaps in its own frame, each built from about
``submap_m`` of travel, matches against the older, fuller one and inserts into both
(Cartographer's scheme).  A finished submap is cropped to what it saw and kept, with the
keyframe it started at, for loop closure; the pose graph then moves it as one rigid piece.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from amiro.core.messages import Pose2D
from amiro.navigation.correlative import SearchWindow
from amiro.navigation.field_match import LikelihoodField
from amiro.navigation.occupancy import LogOddsGrid
from amiro.navigation.poses import between, compose
from amiro.navigation.scan_kernels import lattice_cells, mean_lattice
from amiro.navigation.slam import SlamParams, match_scan

FloatArray = npt.NDArray[np.float64]

# weight of the motion prior against the mean occupancy (0..1) in the correlative guess:
# a 3-sigma move must buy 0.05 more occupancy than staying at the odometry guess
MOTION_PRIOR = 0.011
# the likelihood field is blurred over the scan's extent this much wider (m): the refinement
# moves the pose a few centimetres, the blur reaches 3 sigma (10 cm) beyond a wall
FIELD_MARGIN_M = 0.5


class Submap:
    """A multi-resolution log-odds map anchored at a keyframe (front-end frame)."""

    def __init__(self, anchor: int, anchor_pose: Pose2D, params: SlamParams, travel_m: float):
        self.anchor = anchor  # keyframe index whose graph pose carries this submap
        self.anchor_pose = anchor_pose  # that keyframe's front-end pose
        half = params.max_range + 2.0 * travel_m + 1.0
        origin = (anchor_pose.x - half, anchor_pose.y - half)
        self.levels = [
            LogOddsGrid(
                2 * half,
                2 * half,
                params.resolution * 2**k,
                origin,
                params.free_margin,
                params.clamp,
            )
            for k in range(params.levels)
        ]
        self.travel = 0.0
        self.last_keyframe = anchor

    def insert(self, pose: Pose2D, px: FloatArray, py: FloatArray) -> None:
        c, s = math.cos(pose.theta), math.sin(pose.theta)
        hx = pose.x + c * px - s * py
        hy = pose.y + s * px + c * py
        for grid in self.levels:
            grid.integrate(pose.x, pose.y, hx, hy)

    def finish(self) -> None:
        """Keep only the finest level, cropped to the cells the scans touched."""
        fine = self.levels[0]
        touched = fine.logodds != 0.0
        rows = np.flatnonzero(touched.any(axis=1))
        if rows.size:
            cols = np.flatnonzero(touched.any(axis=0))
            fine.crop(int(rows[0]), int(rows[-1]) + 1, int(cols[0]), int(cols[-1]) + 1)
        self.levels = [fine]


class SubmapFrontEnd:
    """Tracks the pose scan by scan against the active submaps (Hector matching)."""

    def __init__(self, params: SlamParams, submap_m: float = 8.0) -> None:
        self.params = params
        self.submap_m = submap_m
        self.pose = Pose2D()
        self.active: list[Submap] = []
        self._last_odom: Pose2D | None = None
        self._last_insert: Pose2D | None = None
        self._last_step: Pose2D | None = None  # the last motion, when there is no odometry
        self.refused = 0  # matches refused for straying from the odometry guess

    def track(self, px: FloatArray, py: FloatArray, odom: Pose2D | None) -> Pose2D:
        """Match one scan (points in the robot frame) and return the front-end pose: a
        correlative search over the odometry's uncertainty window gives the initial guess
        (real scans can be a metre apart, beyond Gauss-Newton's basin), Gauss-Newton refines
        it; a match further from the odometry guess than ``gate_sigmas`` is refused."""
        p = self.params
        guess = self.pose
        window = None
        gated = True
        if odom is not None and self._last_odom is not None:
            step = between(self._last_odom, odom)
            guess = compose(self.pose, step)
            window = odometry_window(step, p)
        elif odom is None:
            # no odometry: constant velocity, searched over a window wider than the step
            step = self._last_step or Pose2D()
            guess = compose(self.pose, step)
            window = constant_velocity_window(step)
            gated = False
        self._last_odom = odom
        before = self.pose
        if not self.active or px.size < 10:
            self.pose = guess
            self._last_step = between(before, self.pose) if odom is None else None
            return self.pose
        levels = self.active[0].levels
        start = guess
        coarse = levels[-1]
        # Gauss-Newton converges from within about a coarsest cell (at the points' mean
        # range, for the heading); a wider uncertainty (scans a metre apart, a turn) first
        # needs the correlative search
        if (
            window is not None
            and p.search_sigmas * max(window.xy, window.theta * float(np.mean(np.hypot(px, py))))
            > coarse.resolution
        ):
            start = correlative_guess(coarse, px, py, guess, window, p.search_sigmas)
        weight = p.odom_weight if odom is not None else 0.0
        # with the field refinement after it, Hector's finest level adds nothing but time
        hector = levels[1:] if p.field_sigma > 0.0 and len(levels) > 1 else levels
        matched = match_scan(hector, px, py, start, weight, p.iterations)
        if p.field_sigma > 0.0:
            field = LikelihoodField.around_scan(
                levels[0], px, py, matched, FIELD_MARGIN_M, p.field_sigma
            )
            prior = guess if window is not None and odom is not None else None
            sig = (window.xy, window.theta) if window is not None else (1.0, 1.0)
            matched = field.refine(px, py, matched, prior, sig).pose
        if gated and window is not None and _sigmas(matched, guess, window) > p.gate_sigmas:
            self.refused += 1
            matched = guess
        self.pose = matched
        self._last_step = between(before, self.pose) if odom is None else None
        return self.pose

    def should_insert(self) -> bool:
        last = self._last_insert
        if last is None:
            return True
        d = between(last, self.pose)
        p = self.params
        return math.hypot(d.x, d.y) >= p.update_min_d or abs(d.theta) >= p.update_min_a

    def insert(self, px: FloatArray, py: FloatArray, keyframe: int | None) -> Submap | None:
        """Insert the scan at the current pose into the active submaps.  At a new
        ``keyframe``, once the newest submap has seen half its travel, a submap anchored
        there starts and the oldest is finished; that one is returned."""
        step = 0.0
        if self._last_insert is not None:
            step = self._last_insert.distance_to(self.pose)
        self._last_insert = self.pose
        finished = None
        if keyframe is not None and (
            not self.active or self.active[-1].travel >= self.submap_m / 2.0
        ):
            self.active.append(Submap(keyframe, self.pose, self.params, self.submap_m))
            if len(self.active) > 2:
                finished = self.active.pop(0)
                finished.finish()
        for submap in self.active:
            submap.insert(self.pose, px, py)
            submap.travel += step
            if keyframe is not None:
                submap.last_keyframe = keyframe
        return finished


def odometry_window(step: Pose2D, p: SlamParams) -> SearchWindow:
    """One sigma of the odometry's error over ``step`` (the motion between two scans)."""
    d, turn = math.hypot(step.x, step.y), abs(step.theta)
    bx, mx, rx = p.odom_sigma_xy
    bt, mt, rt = p.odom_sigma_theta
    return SearchWindow(bx + mx * d + rx * turn, bt + mt * d + rt * turn)


def constant_velocity_window(step: Pose2D) -> SearchWindow:
    """One sigma of a constant-velocity prediction's error: a robot without odometry may
    stop, turn or speed up between two scans (1 m steps, turns up to 40 degrees in the
    Orebro log)."""
    d = math.hypot(step.x, step.y)
    return SearchWindow(0.4 + 0.3 * d, math.radians(15.0) + 0.3 * abs(step.theta))


def _sigmas(pose: Pose2D, guess: Pose2D, sigma: SearchWindow) -> float:
    """How many sigmas ``pose`` is from ``guess``, in position: a heading gate refused a fifth
    of the matches of the densely sampled Freiburg 079 log (ATE 10.3 m, 1.4 m without)."""
    return pose.distance_to(guess) / sigma.xy


def correlative_guess(
    grid: LogOddsGrid,
    px: FloatArray,
    py: FloatArray,
    guess: Pose2D,
    sigma: SearchWindow,
    sigmas: float,
    max_points: int = 160,
) -> Pose2D:
    """The best pose on a lattice of ``grid``'s cells and rotations (a cell at the reach) within
    ``sigmas`` of ``guess``: mean occupancy at the scan points, less a Gaussian motion prior
    that breaks ties along corridors (Olson 2009)."""
    res = grid.resolution
    stride = max(1, px.size // max_points)
    sx, sy = px[::stride], py[::stride]
    reach = max(float(np.max(np.hypot(sx, sy))), 1.0)
    n_xy = max(1, math.ceil(sigmas * sigma.xy / res))
    angle_step = res / reach
    n_th = max(1, math.ceil(sigmas * sigma.theta / angle_step))
    thetas = guess.theta + angle_step * np.arange(-n_th, n_th + 1.0)
    offsets = np.arange(-n_xy, n_xy + 1, dtype=np.int64)
    rows, cols = lattice_cells(sx, sy, guess.x, guess.y, thetas, grid.origin, res)
    scores = mean_lattice(grid.prob, rows, cols, offsets)
    metres = offsets * res
    d_th = (thetas - guess.theta)[:, None, None] / sigma.theta
    d_xy = (metres[:, None] ** 2 + metres[None, :] ** 2)[None, :, :] / sigma.xy**2
    scores = scores - MOTION_PRIOR * 0.5 * (d_xy + d_th**2)
    k, r, c = np.unravel_index(int(np.argmax(scores)), scores.shape)
    return Pose2D(guess.x + float(metres[c]), guess.y + float(metres[r]), float(thetas[k]))
