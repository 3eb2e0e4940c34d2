"""Monte Carlo localisation in the spirit of ROS ``amcl``.

* motion model: the odometry increment as rotate-translate-rotate with noise that grows
  with the motion (``sample_motion_model_odometry``), so Pepper's drift is absorbed;
* sensor model: the likelihood field on a subsample of the beams;
* adaptive resampling: only when the effective sample size drops, low-variance;
* KLD sampling: as many particles as the spread of the belief needs (min..max);
* recovery (augmented MCL, Thrun et al. 8.3.5): ``w_fast`` and ``w_slow`` track the short-
  and long-term average fit of the scans, and a share ``1 - w_fast / w_slow`` of each
  resampled set is replaced by poses from the free space.  Each injected pose is the best
  fit to the current scan among a few uniform draws (sensor resetting), so a lost filter
  finds the true pose in seconds rather than waiting for a lucky draw;
* ``global_localization``: a uniform belief over the free space, as ROS amcl's service.

The fit of a scan is the mean per-beam probability (not the product), so a few beams on
people or moved furniture lower it a little instead of collapsing it.  Both averages start
at the fit of a scan that matches the map: a filter that starts wrong reads as lost at once.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from statistics import NormalDist

import numpy as np
import numpy.typing as npt

from amiro.core.geometry import wrap_angle
from amiro.core.messages import LaserScan, Pose2D
from amiro.navigation.likelihood import LikelihoodField
from amiro.navigation.poses import between

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class AmclParams:
    min_particles: int = 100
    max_particles: int = 500
    beams: int = 60  # beams used per update (evenly subsampled)
    alpha: tuple[float, float, float, float] = (0.05, 0.02, 0.05, 0.02)  # rot/rot, rot/trans, ...
    init_xy_sigma: float = 0.1
    init_theta_sigma: float = 0.1
    kld_err: float = 0.05
    kld_z: float = 0.99
    bin_xy: float = 0.25
    bin_theta: float = math.radians(10.0)
    alpha_slow: float = 0.001
    alpha_fast: float = 0.1
    fit_trim: float = 0.25  # worst-fitting share of beams left out of the recovery fit
    injection_candidates: int = 10  # uniform draws scored per injected particle (>= 1)
    global_particles: int = 2000  # a uniform start needs more hypotheses than tracking
    update_min_d: float = 0.1  # filter only after this much motion (as amcl's update_min_d)
    update_min_a: float = 0.1
    likelihood_temperature: float = 0.3  # softens the product of correlated beams


class ParticleFilter:
    """Belief over the robot's map pose; feed it odometry poses and scans."""

    def __init__(
        self,
        field: LikelihoodField,
        rng: np.random.Generator,
        params: AmclParams | None = None,
    ) -> None:
        self.field = field
        self.rng = rng
        self.params = params or AmclParams()
        self.particles = np.zeros((0, 3))
        self.weights = np.zeros(0)
        self.w_slow = self.w_fast = field.matched_p
        self._last_odom: Pose2D | None = None  # odometry at the last prediction
        free_rows, free_cols = np.nonzero(field.free)
        self._free_x, self._free_y = field.grid.cell_to_world(free_cols, free_rows)

    # --- initialisation -----------------------------------------------------------------
    def init_pose(self, pose: Pose2D) -> None:
        """Gaussian belief around a known pose."""
        p = self.params
        n = p.max_particles
        noise = self.rng.standard_normal((n, 3)) * [
            p.init_xy_sigma,
            p.init_xy_sigma,
            p.init_theta_sigma,
        ]
        self.particles = np.array([pose.x, pose.y, pose.theta]) + noise
        self.weights = np.full(n, 1.0 / n)
        self._reset_fit()

    def global_localization(self) -> None:
        """Uniform belief over the free space: the robot could be anywhere (ROS amcl's
        ``/global_localization``)."""
        n = max(self.params.global_particles, self.params.max_particles)
        self.particles = self._uniform_poses(n)
        self.weights = np.full(n, 1.0 / n)
        self._reset_fit()

    def _reset_fit(self) -> None:
        self.w_slow = self.w_fast = self.field.matched_p

    def _uniform_poses(self, n: int) -> FloatArray:
        pick = self.rng.integers(0, len(self._free_x), n)
        return np.column_stack(
            (self._free_x[pick], self._free_y[pick], self.rng.uniform(-math.pi, math.pi, n))
        )

    def _recovery_poses(self, n: int, ranges: FloatArray, angles: FloatArray) -> FloatArray:
        """``n`` poses from the free space, each the best fit to the scan of a few uniform
        draws."""
        k = self.params.injection_candidates
        candidates = self._uniform_poses(n * k)
        score = self.field.score(*_endpoints(candidates, ranges, angles))
        best = np.argmax(score.reshape(n, k), axis=1)
        return np.asarray(candidates.reshape(n, k, 3)[np.arange(n), best], dtype=np.float64)

    @property
    def initialised(self) -> bool:
        return len(self.particles) > 0

    # --- prediction ---------------------------------------------------------------------
    def predict(self, odom: Pose2D) -> None:
        """Move every particle by the odometry increment since the previous call, with noise.

        Called just before a correction, as amcl does: the increments in between add up.
        """
        if self._last_odom is None:
            self._last_odom = odom
            return
        delta = between(self._last_odom, odom)
        self._last_odom = odom
        if not self.initialised:
            return
        a1, a2, a3, a4 = self.params.alpha
        trans = math.hypot(delta.x, delta.y)
        rot1 = math.atan2(delta.y, delta.x) if trans > 1e-4 else 0.0
        rot2 = wrap_angle(delta.theta - rot1)
        n = len(self.particles)
        r1 = abs(wrap_angle(rot1))
        r2 = abs(rot2)
        sd_rot1 = math.sqrt(a1 * r1 * r1 + a2 * trans * trans)
        sd_trans = math.sqrt(a3 * trans * trans + a4 * (r1 * r1 + r2 * r2))
        sd_rot2 = math.sqrt(a1 * r2 * r2 + a2 * trans * trans)
        noise = self.rng.standard_normal((n, 3))
        h_rot1 = rot1 + sd_rot1 * noise[:, 0]
        h_trans = trans + sd_trans * noise[:, 1]
        h_rot2 = rot2 + sd_rot2 * noise[:, 2]
        th = self.particles[:, 2]
        self.particles[:, 0] += h_trans * np.cos(th + h_rot1)
        self.particles[:, 1] += h_trans * np.sin(th + h_rot1)
        self.particles[:, 2] = th + h_rot1 + h_rot2

    def moved_enough(self, odom: Pose2D) -> bool:
        """Whether odometry moved far enough since the last prediction to filter again."""
        if self._last_odom is None:
            return True
        delta = between(self._last_odom, odom)
        p = self.params
        return math.hypot(delta.x, delta.y) >= p.update_min_d or abs(delta.theta) >= p.update_min_a

    # --- correction ---------------------------------------------------------------------
    def correct(self, scan: LaserScan) -> None:
        """Weight the particles by the scan, inject random ones if lost, resample if needed."""
        if not self.initialised:
            return
        ranges, angles = _usable_beams(scan, self.params.beams)
        if ranges.size == 0:
            return
        logp = self.field.log_likelihoods(*_endpoints(self.particles, ranges, angles))
        logw = self.params.likelihood_temperature * logp.sum(axis=1, dtype=np.float64)
        logw += np.log(self.weights + 1e-300)
        w = np.exp(logw - logw.max())
        self.weights = w / w.sum()
        self._track_fit(float(self.weights @ self._trimmed_fit(logp)))
        n_eff = 1.0 / float(np.sum(self.weights**2))
        if n_eff < 0.5 * len(self.weights) or self.inject_share() > 0.0:
            self._resample(ranges, angles)

    def _trimmed_fit(self, logp: FloatArray) -> FloatArray:
        """Per particle, the mean probability of its best-fitting beams: beams that hit
        obstacles the map lacks (boxes, people) say nothing about being lost, so the worst
        ``fit_trim`` share is left out of the fit that drives recovery."""
        p = np.exp(logp)
        keep = max(1, round(p.shape[1] * (1.0 - self.params.fit_trim)))
        if keep >= p.shape[1]:
            return np.asarray(p.mean(axis=1), dtype=np.float64)
        best = np.partition(p, p.shape[1] - keep, axis=1)[:, p.shape[1] - keep :]
        return np.asarray(best.mean(axis=1), dtype=np.float64)

    def _track_fit(self, fit: float) -> None:
        """Short- and long-term averages of how well scans fit (mean per-beam probability)."""
        p = self.params
        self.w_slow += p.alpha_slow * (fit - self.w_slow)
        self.w_fast += p.alpha_fast * (fit - self.w_fast)

    def inject_share(self) -> float:
        """Share of the next resampled set drawn from the free space: how lost we are."""
        return max(0.0, 1.0 - self.w_fast / self.w_slow)

    def _resample(self, ranges: FloatArray, angles: FloatArray) -> None:
        """Low-variance resampling to a KLD-sized set, with random particles when lost."""
        n_old = len(self.weights)
        positions = (self.rng.uniform() + np.arange(n_old)) / n_old
        idx = np.minimum(np.searchsorted(np.cumsum(self.weights), positions), n_old - 1)
        chosen = self.particles[idx]
        n = self._kld_size(chosen)
        chosen = chosen[self.rng.permutation(len(chosen))[:n]] if n < len(chosen) else chosen
        if n > len(chosen):
            chosen = chosen[self.rng.integers(0, len(chosen), n)]
        n_random = round(self.inject_share() * n)
        if n_random:
            chosen[:n_random] = self._recovery_poses(n_random, ranges, angles)
        self.particles = chosen.copy()
        self.weights = np.full(len(chosen), 1.0 / len(chosen))

    def _kld_size(self, particles: FloatArray) -> int:
        """Fox's KLD bound on the sample count for the number of occupied histogram bins."""
        p = self.params
        k = len(np.unique(_bins(particles, p.bin_xy, p.bin_theta), axis=0))
        if k <= 1:
            return p.min_particles
        a = 2.0 / (9.0 * (k - 1))
        z = NormalDist().inv_cdf(p.kld_z)
        bound = (k - 1) / (2.0 * p.kld_err) * (1.0 - a + math.sqrt(a) * z) ** 3
        return int(min(p.max_particles, max(p.min_particles, math.ceil(bound))))

    # --- estimate -----------------------------------------------------------------------
    def estimate(self) -> Pose2D:
        """Weighted mean of the heaviest cluster: the pose bin (0.5 m, 30 degrees) holding
        the most weight, widened to the particles near it.  After resampling the weights
        are uniform, so the heaviest bin is the densest one; injected strays never win."""
        keys = _bins(self.particles, _CLUSTER_XY, _CLUSTER_THETA)
        _, bin_of = np.unique(keys, axis=0, return_inverse=True)
        bin_of = bin_of.reshape(-1)
        best = int(np.argmax(np.bincount(bin_of, weights=self.weights)))
        seed = _weighted_pose(self.particles, self.weights * (bin_of == best))
        near = (
            np.hypot(self.particles[:, 0] - seed.x, self.particles[:, 1] - seed.y) < _CLUSTER_XY
        ) & (np.abs(wrap_angle_array(self.particles[:, 2] - seed.theta)) < _CLUSTER_THETA)
        return _weighted_pose(self.particles, self.weights * near)

    def spread(self) -> float:
        """The belief's size (m): the distance from the estimate holding half the weight.

        A median, so the few particles injected into a healthy filter do not make it look
        wide (a wide belief is filtered on every scan, which would inject again)."""
        est = self.estimate()
        dist = np.hypot(self.particles[:, 0] - est.x, self.particles[:, 1] - est.y)
        order = np.argsort(dist)
        half = min(int(np.searchsorted(np.cumsum(self.weights[order]), 0.5)), len(order) - 1)
        return float(dist[order[half]])


_CLUSTER_XY = 0.5
_CLUSTER_THETA = math.radians(30.0)


def _bins(particles: FloatArray, bin_xy: float, bin_theta: float) -> FloatArray:
    """Histogram bin of every particle, one row of (x, y, theta) bin indices each."""
    return np.column_stack(
        (
            np.floor(particles[:, 0] / bin_xy),
            np.floor(particles[:, 1] / bin_xy),
            np.floor(wrap_angle_array(particles[:, 2]) / bin_theta),
        )
    )


def _weighted_pose(particles: FloatArray, weights: FloatArray) -> Pose2D:
    """Weighted mean position and circular-mean heading."""
    w = weights / weights.sum()
    th = particles[:, 2]
    return Pose2D(
        float(w @ particles[:, 0]),
        float(w @ particles[:, 1]),
        math.atan2(float(w @ np.sin(th)), float(w @ np.cos(th))),
    )


def wrap_angle_array(a: FloatArray) -> FloatArray:
    return np.asarray((a + math.pi) % (2.0 * math.pi) - math.pi)


def _endpoints(
    poses: FloatArray, ranges: FloatArray, angles: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """World coordinates of every beam's endpoint from every pose, shaped (poses, beams)."""
    th = poses[:, 2:3] + angles[None, :]
    xs = poses[:, 0:1] + ranges[None, :] * np.cos(th)
    ys = poses[:, 1:2] + ranges[None, :] * np.sin(th)
    return xs, ys


def _usable_beams(scan: LaserScan, count: int) -> tuple[FloatArray, FloatArray]:
    """Up to ``count`` evenly spaced beams with a finite, in-range return."""
    step = max(1, len(scan.ranges) // count)
    ranges = scan.ranges[::step]
    angles = scan.angles()[::step]
    ok = np.isfinite(ranges) & (ranges > scan.range_min) & (ranges < scan.range_max)
    return ranges[ok], angles[ok]
