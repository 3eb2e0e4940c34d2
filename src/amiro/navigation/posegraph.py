"""A 2D pose graph (SE(2) nodes, relative-pose edges) optimised with sparse Gauss-Newton.

Graph SLAM's back end: keyframe poses are the unknowns, every edge says "node j seen from
node i is at z, with this information matrix".  Levenberg-Marquardt iterations build the
sparse Jacobian of all edge residuals at once (numpy) and solve the normal equations with
scipy's sparse LU; loop edges get Cauchy weights (iteratively reweighted) so one false loop
closure cannot bend the whole map.  The first node is held fixed (the map frame).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt
import scipy.sparse as sp
from scipy.sparse.linalg import spsolve

from amiro.core.messages import Pose2D

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]


def _wrap(a: FloatArray) -> FloatArray:
    return np.asarray(np.arctan2(np.sin(a), np.cos(a)))


@dataclass
class _Edges:
    i: list[int] = field(default_factory=list)
    j: list[int] = field(default_factory=list)
    z: list[tuple[float, float, float]] = field(default_factory=list)
    sqrt_info: list[tuple[float, float, float]] = field(default_factory=list)
    robust: list[bool] = field(default_factory=list)


class PoseGraph:
    """Nodes are added in order; edges carry diagonal standard deviations (x, y, theta)."""

    def __init__(self, cauchy_scale: float = 3.0) -> None:
        self.poses = np.zeros((0, 3))
        self.cauchy_scale = cauchy_scale  # in standard deviations
        self._edges = _Edges()

    def add_node(self, pose: Pose2D) -> int:
        self.poses = np.vstack((self.poses, [pose.x, pose.y, pose.theta]))
        return len(self.poses) - 1

    def add_edge(
        self,
        i: int,
        j: int,
        z: Pose2D,
        sigma: tuple[float, float, float],
        robust: bool = False,
    ) -> None:
        """Node ``j`` measured at ``z`` in node ``i``'s frame."""
        e = self._edges
        e.i.append(i)
        e.j.append(j)
        e.z.append((z.x, z.y, z.theta))
        e.sqrt_info.append((1.0 / sigma[0], 1.0 / sigma[1], 1.0 / sigma[2]))
        e.robust.append(robust)

    @property
    def edge_count(self) -> int:
        return len(self._edges.i)

    def pose(self, k: int) -> Pose2D:
        x, y, th = self.poses[k]
        return Pose2D(float(x), float(y), float(th))

    def optimize(self, iterations: int = 50, tol: float = 1e-4) -> float:
        """Levenberg-Marquardt from the current poses; returns the final weighted cost."""
        if self.edge_count == 0 or len(self.poses) < 2:
            return 0.0
        e = self._edges
        ii, jj = np.array(e.i, np.intp), np.array(e.j, np.intp)
        z = np.array(e.z)
        sqrt_info = np.array(e.sqrt_info)
        robust = np.array(e.robust)
        lam = 1e-4
        # graduated robustness: the Cauchy scale starts at the largest robust residual and
        # shrinks, so true loops far from the first guess are not mistaken for outliers
        scale = max(
            self.cauchy_scale, float(np.sqrt(self._robust_sq(ii, jj, z, sqrt_info, robust)))
        )
        cost = self._cost(self.poses, ii, jj, z, sqrt_info, robust, scale)
        for _ in range(iterations):
            res, jac = _residuals_and_jacobian(self.poses, ii, jj, z, sqrt_info)
            w = _cauchy_weights(res, robust, scale)
            jac = jac.tocsc()[:, 3:]  # node 0 is fixed: drop its columns
            jw = (sp.diags(np.repeat(w, 3)) @ jac).tocsc()
            hess = (jac.T @ jw).tocsc()
            grad = jw.T @ res.reshape(-1)
            damp = sp.diags(lam * (hess.diagonal() + 1e-9))
            step = spsolve((hess + damp).tocsc(), -grad).reshape(-1, 3)
            trial = self.poses.copy()
            trial[1:] += step
            trial[:, 2] = _wrap(trial[:, 2])
            new_cost = self._cost(trial, ii, jj, z, sqrt_info, robust, scale)
            converged = False
            if new_cost < cost:
                converged = (cost - new_cost) / max(cost, 1e-12) < tol
                self.poses, cost, lam = trial, new_cost, max(lam / 10.0, 1e-7)
            else:
                lam *= 10.0
                converged = lam > 1e6
            if converged:  # settled at this scale: tighten it, or stop at the final one
                if scale <= self.cauchy_scale:
                    break
                scale = max(self.cauchy_scale, scale * 0.3)
                lam = 1e-4
                cost = self._cost(self.poses, ii, jj, z, sqrt_info, robust, scale)
        return cost

    def _robust_sq(
        self,
        ii: IntArray,
        jj: IntArray,
        z: FloatArray,
        sqrt_info: FloatArray,
        robust: npt.NDArray[np.bool_],
    ) -> float:
        if not robust.any():
            return 0.0
        res = _residuals(self.poses, ii[robust], jj[robust], z[robust], sqrt_info[robust])
        return float(np.max(np.sum(res**2, axis=1)))

    def _cost(
        self,
        poses: FloatArray,
        ii: IntArray,
        jj: IntArray,
        z: FloatArray,
        sqrt_info: FloatArray,
        robust: npt.NDArray[np.bool_],
        scale: float,
    ) -> float:
        res = _residuals(poses, ii, jj, z, sqrt_info)
        sq = np.sum(res**2, axis=1)
        c2 = scale**2
        per_edge = np.where(robust, c2 * np.log1p(sq / c2), sq)
        return float(per_edge.sum())


def _residuals(
    poses: FloatArray, ii: IntArray, jj: IntArray, z: FloatArray, sqrt_info: FloatArray
) -> FloatArray:
    return _residuals_and_jacobian(poses, ii, jj, z, sqrt_info, with_jacobian=False)[0]


def _residuals_and_jacobian(
    poses: FloatArray,
    ii: IntArray,
    jj: IntArray,
    z: FloatArray,
    sqrt_info: FloatArray,
    with_jacobian: bool = True,
) -> tuple[FloatArray, sp.csr_matrix]:
    """Whitened residuals ``Rz^T (Ri^T (tj - ti) - tz), thj - thi - thz`` per edge, and their
    sparse Jacobian with respect to all poses (3 columns per node)."""
    xi, xj = poses[ii], poses[jj]
    ci, si = np.cos(xi[:, 2]), np.sin(xi[:, 2])
    cz, sz = np.cos(z[:, 2]), np.sin(z[:, 2])
    dx, dy = xj[:, 0] - xi[:, 0], xj[:, 1] - xi[:, 1]
    lx, ly = ci * dx + si * dy, -si * dx + ci * dy  # tj in node i's frame
    ex, ey = lx - z[:, 0], ly - z[:, 1]
    res = np.column_stack(
        (cz * ex + sz * ey, -sz * ex + cz * ey, _wrap(xj[:, 2] - xi[:, 2] - z[:, 2]))
    )
    res *= sqrt_info
    if not with_jacobian:
        return res, sp.csr_matrix((0, 0))
    m = len(ii)
    # d(lx, ly) / d(ti, thi, tj): Ri^T rotation and its derivative
    dl_dthi = np.column_stack((-si * dx + ci * dy, -ci * dx - si * dy))
    blocks_i = np.zeros((m, 3, 3))
    blocks_j = np.zeros((m, 3, 3))
    rt = np.stack((np.column_stack((ci, si)), np.column_stack((-si, ci))), axis=1)  # Ri^T
    rz = np.stack((np.column_stack((cz, sz)), np.column_stack((-sz, cz))), axis=1)  # Rz^T
    rzrt = rz @ rt
    blocks_i[:, :2, :2] = -rzrt
    blocks_i[:, :2, 2] = np.einsum("mab,mb->ma", rz, dl_dthi)
    blocks_i[:, 2, 2] = -1.0
    blocks_j[:, :2, :2] = rzrt
    blocks_j[:, 2, 2] = 1.0
    blocks_i *= sqrt_info[:, :, None]
    blocks_j *= sqrt_info[:, :, None]
    rows = np.repeat(np.arange(3 * m).reshape(m, 3), 3, axis=1)  # (m, 9) row per entry
    cols_i = (3 * ii)[:, None] + np.tile(np.arange(3), 3)[None, :]
    cols_j = (3 * jj)[:, None] + np.tile(np.arange(3), 3)[None, :]
    data = np.concatenate((blocks_i.reshape(m, 9), blocks_j.reshape(m, 9)), axis=1)
    jac = sp.csr_matrix(
        (
            data.reshape(-1),
            (
                np.concatenate((rows, rows), axis=1).reshape(-1),
                np.concatenate((cols_i, cols_j), axis=1).reshape(-1),
            ),
        ),
        shape=(3 * m, poses.size),
    )
    return res, jac


def _cauchy_weights(res: FloatArray, robust: npt.NDArray[np.bool_], scale: float) -> FloatArray:
    """IRLS weights: 1 for ordinary edges, ``1 / (1 + r^2 / c^2)`` for robust ones."""
    sq = np.sum(res**2, axis=1)
    return np.where(robust, 1.0 / (1.0 + sq / scale**2), 1.0)
