"""Sub-cell scan refinement on a smooth likelihood field, with the odometry where it is blind.

Hector's matcher climbs the bilinear-interpolated occupancy probability: a wall is one or
two cells wide there, so the gradient vanishes a cell away and the optimum snaps to cell
edges.  Here the submap's hits are blurred into a Gaussian ridge (``FIELD_SIGMA_M``), as the
likelihood-field matchers do (Hector, Cartographer's Ceres matcher, Olson's), and the pose is
refined by Gauss-Newton on it: a smooth cost whose minimum lies between cells.

The match's Hessian says what the scan constrains.  In a corridor the scan pins the pose
across the corridor and the heading but not along it; there the scan's information is
nearly zero and the odometry's takes over (the two are fused as information: scan Hessian
over its residual variance plus the odometry's inverse covariance), so the match cannot
slide along the corridor (degeneracy-aware matching, Zhang et al. 2016).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from scipy.ndimage import gaussian_filter

from amiro.core.geometry import wrap_angle
from amiro.core.messages import Pose2D
from amiro.navigation.occupancy import LogOddsGrid, bilinear

FloatArray = npt.NDArray[np.float64]

# the ridge's one-sigma half-width, under a cell of the 5 cm grid: the front end's relation
# error per metre on seven real logs (front end alone) is lowest at 2.5-3.5 cm (mean 0.044 m),
# 5 cm gives 0.049 m, 10 cm loses the matches (the ridges of near walls merge)
FIELD_SIGMA_M = 0.035
# a residual's standard deviation on the field (0..1): turns the scan's Hessian into an
# information matrix commensurate with the odometry's (0.2-0.5 give the same relation error)
RESIDUAL_SIGMA = 0.3
# a direction with less than this share of the best-constrained one's information is left
# to the odometry (degeneracy-aware matching, Zhang et al. 2016): an ideal corridor's
# staircase walls give 0.7 % along it
DEGENERATE_RATIO = 0.02


@dataclass(frozen=True)
class FieldMatch:
    pose: Pose2D
    information: FloatArray  # 3x3, the scan's alone (x, y, theta; map frame)


class LikelihoodField:
    """The blurred hits of a log-odds grid over a box (lower-left ``lo``, upper-right ``hi``,
    map frame): the scan's own extent, so the blur costs what the scan covers."""

    def __init__(
        self,
        grid: LogOddsGrid,
        lo: tuple[float, float],
        hi: tuple[float, float],
        sigma_m: float = FIELD_SIGMA_M,
    ) -> None:
        res = grid.resolution
        h, w = grid.logodds.shape
        c0 = max(0, int((lo[0] - grid.origin[0]) / res))
        r0 = max(0, int((lo[1] - grid.origin[1]) / res))
        c1 = min(w, int((hi[0] - grid.origin[0]) / res) + 1)
        r1 = min(h, int((hi[1] - grid.origin[1]) / res) + 1)
        hits = (grid.logodds[r0:r1, c0:c1] > 0.0).astype(np.float32)
        sigma = sigma_m / res
        # a line of hits blurred in 2D peaks at 1 / (sqrt(2 pi) sigma): scaled back to ~1
        blurred = gaussian_filter(hits, sigma, truncate=3.0) * (math.sqrt(2.0 * math.pi) * sigma)
        self.field = np.minimum(blurred, 1.0).astype(np.float32)
        self.resolution = res
        self.origin = (grid.origin[0] + c0 * res, grid.origin[1] + r0 * res)

    def refine(
        self,
        px: FloatArray,
        py: FloatArray,
        start: Pose2D,
        prior: Pose2D | None,
        prior_sigma: tuple[float, float],
        iterations: int = 10,
    ) -> FieldMatch:
        """Gauss-Newton from ``start``: the scan on the field, plus ``prior`` (the odometry
        guess, one sigma ``prior_sigma`` = (xy, theta)) as information."""
        xi = np.array([start.x, start.y, start.theta])
        prior_info = np.zeros((3, 3))
        mu = xi.copy()
        if prior is not None:
            mu = np.array([prior.x, prior.y, prior.theta])
            sxy, sth = prior_sigma
            prior_info = np.diag([1.0 / sxy**2, 1.0 / sxy**2, 1.0 / sth**2])
        scan_info = np.zeros((3, 3))
        # heading in metres at the scan's mean range, so that the eigenvalues compare
        scale = np.array([1.0, 1.0, max(float(np.mean(np.hypot(px, py))), 1.0)])
        for _ in range(iterations):
            jac, r = self._residuals(px, py, xi)
            scan_info = jac.T @ jac / RESIDUAL_SIGMA**2
            keep = _constrained(scan_info, scale)
            d_prior = xi - mu
            d_prior[2] = wrap_angle(float(d_prior[2]))
            hess = keep @ scan_info @ keep + prior_info + 1e-9 * np.eye(3)
            grad = keep @ (jac.T @ r) / RESIDUAL_SIGMA**2 - prior_info @ d_prior
            try:
                step = np.linalg.solve(hess, grad)
            except np.linalg.LinAlgError:
                break
            step[:2] = np.clip(step[:2], -0.1, 0.1)
            step[2] = float(np.clip(step[2], -0.05, 0.05))
            xi = xi + step
            if abs(step[0]) + abs(step[1]) < 1e-3 and abs(step[2]) < 1e-4:
                break
        pose = Pose2D(float(xi[0]), float(xi[1]), wrap_angle(float(xi[2])))
        return FieldMatch(pose, scan_info)

    @classmethod
    def around_scan(
        cls,
        grid: LogOddsGrid,
        px: FloatArray,
        py: FloatArray,
        pose: Pose2D,
        margin: float,
        sigma_m: float = FIELD_SIGMA_M,
    ) -> LikelihoodField:
        """The field under the scan (points px, py in the robot frame) seen from ``pose``,
        ``margin`` metres wider each side: the refinement moves the scan less than that."""
        c, s = math.cos(pose.theta), math.sin(pose.theta)
        wx = pose.x + c * px - s * py
        wy = pose.y + s * px + c * py
        lo = (float(wx.min()) - margin, float(wy.min()) - margin)
        hi = (float(wx.max()) + margin, float(wy.max()) + margin)
        return cls(grid, lo, hi, sigma_m)

    def _residuals(
        self, px: FloatArray, py: FloatArray, xi: FloatArray
    ) -> tuple[FloatArray, FloatArray]:
        c, s = math.cos(xi[2]), math.sin(xi[2])
        wx = xi[0] + c * px - s * py
        wy = xi[1] + s * px + c * py
        res = self.resolution
        m, du, dv = bilinear(self.field, (wx - self.origin[0]) / res, (wy - self.origin[1]) / res)
        gx, gy = du / res, dv / res
        dtheta = gx * (-s * px - c * py) + gy * (c * px - s * py)
        return np.column_stack((gx, gy, dtheta)), 1.0 - m


def _constrained(info: FloatArray, scale: FloatArray) -> FloatArray:
    """The projection onto the directions the scan constrains: those whose information is at
    least ``DEGENERATE_RATIO`` of the best-constrained one's (in metres, the heading scaled by
    ``scale``).  A corridor's walls, drawn as cells, still give a little information along
    it (their staircase), enough to outweigh the odometry and let the match slide."""
    s_inv = 1.0 / scale
    scaled = info * s_inv[:, None] * s_inv[None, :]
    values, vectors = np.linalg.eigh(scaled)
    good = vectors[:, values >= DEGENERATE_RATIO * max(float(values[-1]), 1e-12)]
    proj = good @ good.T
    # back to the original units: P' = S^-1 P S
    return np.asarray(proj * s_inv[:, None] * scale[None, :])
