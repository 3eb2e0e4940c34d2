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
from amiro.navigation.occupancy import LogOddsGrid
from amiro.navigation.poses import between, compose
from amiro.navigation.slam import SlamParams, match_scan

FloatArray = npt.NDArray[np.float64]


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
        seen = np.nonzero(fine.logodds)
        if seen[0].size:
            r0, r1 = int(seen[0].min()), int(seen[0].max()) + 1
            c0, c1 = int(seen[1].min()), int(seen[1].max()) + 1
            fine.logodds = fine.logodds[r0:r1, c0:c1].copy()
            fine.prob = fine.prob[r0:r1, c0:c1].copy()
            res = fine.resolution
            fine.origin = (fine.origin[0] + c0 * res, fine.origin[1] + r0 * res)
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
        self.refused = 0  # matches refused for straying from the odometry guess

    def track(self, px: FloatArray, py: FloatArray, odom: Pose2D | None) -> Pose2D:
        """Match one scan (points in the robot frame) and return the front-end pose."""
        guess = self.pose
        if odom is not None and self._last_odom is not None:
            guess = compose(self.pose, between(self._last_odom, odom))
        self._last_odom = odom
        if self.active and px.size >= 10:
            p = self.params
            weight = p.odom_weight if odom is not None else 0.0
            matched = match_scan(self.active[0].levels, px, py, guess, weight, p.iterations)
            # odometry is off by millimetres over one scan's motion: a match decimetres from
            # its guess has slid along a self-similar corridor (or onto a door one further)
            if odom is not None and matched.distance_to(guess) > p.max_correction_m:
                self.refused += 1
                matched = guess
            self.pose = matched
        else:
            self.pose = guess
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
