"""2D lidar SLAM in the spirit of Hector SLAM: multi-resolution scan-to-map matching.

Every scan is aligned to the map built so far by Gauss-Newton on the bilinear-interpolated
occupancy probability, coarse grid first (wide basin of convergence), then finer ones
(precision).  Odometry, when there is any, gives the initial guess and a weak prior that keeps
the match from sliding along featureless corridors; without it the previous pose is the
guess, so it also works from the lidar alone.  The map is then updated with log-odds.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from amiro.core.geometry import wrap_angle
from amiro.core.gridmap import GridMap
from amiro.core.messages import Pose2D
from amiro.navigation.occupancy import L_CLAMP, LogOddsGrid, bilinear
from amiro.navigation.poses import between, compose

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class SlamParams:
    resolution: float = 0.05
    levels: int = 3  # each coarser level doubles the cell size
    size_m: float = 100.0  # square map extent, centred on the first pose
    iterations: int = 6  # Gauss-Newton steps per level
    max_range: float = 12.0
    update_min_d: float = 0.1  # map update only after this much motion (m / rad)
    update_min_a: float = 0.1
    odom_weight: float = 20.0  # prior strength on the odometry guess (per level, scaled)
    free_margin: float = 0.0  # fraction of the range (see LogOddsGrid); 0: one cell
    clamp: float = L_CLAMP  # log-odds bound of the matching maps (see LogOddsGrid)
    # one-sigma error of odometry over one scan step: (base, per metre, per radian moved);
    # real wheel odometry over a 1 m step is off by ~5 cm and a few degrees
    odom_sigma_xy: tuple[float, float, float] = (0.03, 0.1, 0.05)
    odom_sigma_theta: tuple[float, float, float] = (0.01, 0.03, 0.1)
    search_sigmas: float = 3.0  # half-width of the correlative search around the guess
    gate_sigmas: float = math.inf  # a match this many sigmas from the odometry guess is refused
    # > 0: refine on a likelihood field blurred this much (m; see field_match.py)
    field_sigma: float = 0.0


class HectorSlam:
    """Feed ``update(ranges, angles, odom)`` per scan; read ``pose`` and ``map()``."""

    def __init__(self, params: SlamParams | None = None, start: Pose2D | None = None) -> None:
        self.params = p = params or SlamParams()
        self.pose = start or Pose2D()
        half = p.size_m / 2.0
        origin = (self.pose.x - half, self.pose.y - half)
        self.levels = [
            LogOddsGrid(p.size_m, p.size_m, p.resolution * 2**k, origin, p.free_margin, p.clamp)
            for k in range(p.levels)
        ]
        self._last_odom: Pose2D | None = None
        self._last_map_pose: Pose2D | None = None
        self.scans = 0

    def update(self, ranges: FloatArray, angles: FloatArray, odom: Pose2D | None = None) -> Pose2D:
        """Add one scan (ranges in metres, beam angles in the robot frame); returns the pose."""
        p = self.params
        ok = np.isfinite(ranges) & (ranges > 0.05) & (ranges < p.max_range)
        px = ranges[ok] * np.cos(angles[ok])
        py = ranges[ok] * np.sin(angles[ok])
        guess = self.pose
        if odom is not None and self._last_odom is not None:
            guess = compose(self.pose, between(self._last_odom, odom))
        self._last_odom = odom
        if self.scans > 0 and px.size >= 10:
            self.pose = self._match(px, py, guess, use_prior=odom is not None)
        else:
            self.pose = guess
        self.scans += 1
        if self._should_integrate():
            self._integrate(px, py)
        return self.pose

    def _should_integrate(self) -> bool:
        last = self._last_map_pose
        if last is None:
            return True
        d = between(last, self.pose)
        return (
            math.hypot(d.x, d.y) >= self.params.update_min_d
            or abs(d.theta) >= self.params.update_min_a
        )

    def _integrate(self, px: FloatArray, py: FloatArray) -> None:
        c, s = math.cos(self.pose.theta), math.sin(self.pose.theta)
        hx = self.pose.x + c * px - s * py
        hy = self.pose.y + s * px + c * py
        for grid in self.levels:
            grid.integrate(self.pose.x, self.pose.y, hx, hy)
        self._last_map_pose = self.pose

    def _match(self, px: FloatArray, py: FloatArray, guess: Pose2D, use_prior: bool) -> Pose2D:
        p = self.params
        weight = p.odom_weight if use_prior else 0.0
        return match_scan(self.levels, px, py, guess, weight, p.iterations)

    def map(self) -> GridMap:
        return self.levels[0].to_gridmap()


def match_scan(
    levels: list[LogOddsGrid],
    px: FloatArray,
    py: FloatArray,
    guess: Pose2D,
    prior_weight: float,
    iterations: int,
) -> Pose2D:
    """Hector's multi-resolution scan-to-map match: Gauss-Newton on each grid of ``levels``
    (finest first in the list), coarsest first; ``prior_weight`` (per metre of cell size)
    pulls towards ``guess``."""
    xi = np.array([guess.x, guess.y, guess.theta])
    prior = xi.copy()
    for grid in reversed(levels):
        prob = grid.prob
        weight = prior_weight * grid.resolution
        for _ in range(iterations):
            step = _gauss_newton_step(prob, grid, px, py, xi, prior, weight)
            xi = xi + step
            if abs(step[0]) + abs(step[1]) < 1e-4 and abs(step[2]) < 1e-4:
                break
    return Pose2D(float(xi[0]), float(xi[1]), wrap_angle(float(xi[2])))


def _gauss_newton_step(
    prob: npt.NDArray[np.float32],
    grid: LogOddsGrid,
    px: FloatArray,
    py: FloatArray,
    xi: FloatArray,
    prior: FloatArray,
    weight: float,
) -> FloatArray:
    """One Gauss-Newton step on sum (1 - M(S_i(xi)))^2 + weight * |xi - prior|^2."""
    c, s = math.cos(xi[2]), math.sin(xi[2])
    wx = xi[0] + c * px - s * py
    wy = xi[1] + s * px + c * py
    res = grid.resolution
    m, du, dv = bilinear(prob, (wx - grid.origin[0]) / res, (wy - grid.origin[1]) / res)
    gx, gy = du / res, dv / res
    dtheta = gx * (-s * px - c * py) + gy * (c * px - s * py)
    jac = np.column_stack((gx, gy, dtheta))
    r = 1.0 - m
    hess = jac.T @ jac + weight * np.diag([1.0, 1.0, 1.0])
    grad = jac.T @ r + weight * (prior - xi) * np.array([1.0, 1.0, 1.0])
    try:
        step = np.linalg.solve(hess + 1e-9 * np.eye(3), grad)
    except np.linalg.LinAlgError:
        return np.zeros(3)
    step[:2] = np.clip(step[:2], -0.3, 0.3)
    step[2] = float(np.clip(step[2], -0.2, 0.2))
    return np.asarray(step)
