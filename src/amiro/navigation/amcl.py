"""Monte Carlo localisation in the spirit of ROS ``amcl``.

* motion model: the odometry increment as rotate-translate-rotate with noise that grows
  with the motion (``sample_motion_model_odometry``), so Pepper's drift is absorbed;
* sensor model: the likelihood field on a subsample of the beams;
* adaptive resampling: only when the effective sample size drops, low-variance;
* KLD sampling: as many particles as the spread of the belief needs (min..max);
* recovery: random particles injected when the short-term average likelihood falls below
  the long-term one (augmented MCL), which also finds the robot from a wrong initial pose.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from statistics import NormalDist

import numpy as np
import numpy.typing as npt

from amiro.core.messages import LaserScan, Pose2D
from amiro.navigation.likelihood import LikelihoodField
from amiro.navigation.poses import between
from amiro.sim.geometry import wrap_angle

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
    lost_ratio: float = 0.3  # inject once short-term fit < this share of the long-term fit
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
        self.w_slow = 0.0
        self.w_fast = 0.0
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

    def init_global(self) -> None:
        """Uniform belief over the free space: the robot could be anywhere."""
        n = self.params.max_particles
        self.particles = self._random_particles(n)
        self.weights = np.full(n, 1.0 / n)

    def _random_particles(self, n: int) -> FloatArray:
        pick = self.rng.integers(0, len(self._free_x), n)
        return np.column_stack(
            (self._free_x[pick], self._free_y[pick], self.rng.uniform(-math.pi, math.pi, n))
        )

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
        th = self.particles[:, 2:3] + angles[None, :]
        xs = self.particles[:, 0:1] + ranges[None, :] * np.cos(th)
        ys = self.particles[:, 1:2] + ranges[None, :] * np.sin(th)
        logw = self.params.likelihood_temperature * self.field.score(xs, ys)
        logw += np.log(self.weights + 1e-300)
        top = float(logw.max())
        w = np.exp(logw - top)
        total = float(w.sum())
        self.weights = w / total
        self._track_likelihood(scan_mean_logp=(top + math.log(total)) / max(1, ranges.size))
        n_eff = 1.0 / float(np.sum(self.weights**2))
        if n_eff < 0.5 * len(self.weights) or self._inject_share() > 0.0:
            self._resample()

    def _track_likelihood(self, scan_mean_logp: float) -> None:
        """Short- and long-term averages of how well scans fit (per beam, as a probability)."""
        avg = math.exp(scan_mean_logp / self.params.likelihood_temperature)
        p = self.params
        self.w_slow = (
            avg if self.w_slow == 0.0 else self.w_slow + p.alpha_slow * (avg - self.w_slow)
        )
        self.w_fast = (
            avg if self.w_fast == 0.0 else self.w_fast + p.alpha_fast * (avg - self.w_fast)
        )

    def _inject_share(self) -> float:
        if self.w_slow <= 0.0:
            return 0.0
        return max(0.0, 1.0 - self.w_fast / (self.params.lost_ratio * self.w_slow))

    def _resample(self) -> None:
        """Low-variance resampling to a KLD-sized set, with random particles when lost."""
        n_old = len(self.weights)
        positions = (self.rng.uniform() + np.arange(n_old)) / n_old
        idx = np.minimum(np.searchsorted(np.cumsum(self.weights), positions), n_old - 1)
        chosen = self.particles[idx]
        n = self._kld_size(chosen)
        chosen = chosen[self.rng.permutation(len(chosen))[:n]] if n < len(chosen) else chosen
        if n > len(chosen):
            chosen = chosen[self.rng.integers(0, len(chosen), n)]
        n_random = round(self._inject_share() * n)
        if n_random:
            chosen[:n_random] = self._random_particles(n_random)
            self.w_fast = self.w_slow  # as amcl: one injection per detected drop
        self.particles = chosen.copy()
        self.weights = np.full(len(chosen), 1.0 / len(chosen))

    def _kld_size(self, particles: FloatArray) -> int:
        """Fox's KLD bound on the sample count for the number of occupied histogram bins."""
        p = self.params
        bins = np.column_stack(
            (
                np.floor(particles[:, 0] / p.bin_xy),
                np.floor(particles[:, 1] / p.bin_xy),
                np.floor(wrap_angle_array(particles[:, 2]) / p.bin_theta),
            )
        )
        k = len(np.unique(bins, axis=0))
        if k <= 1:
            return p.min_particles
        a = 2.0 / (9.0 * (k - 1))
        z = NormalDist().inv_cdf(p.kld_z)
        bound = (k - 1) / (2.0 * p.kld_err) * (1.0 - a + math.sqrt(a) * z) ** 3
        return int(min(p.max_particles, max(p.min_particles, math.ceil(bound))))

    # --- estimate -----------------------------------------------------------------------
    def estimate(self) -> Pose2D:
        """Weighted mean of the particles near the most likely one (the main cluster)."""
        best = self.particles[int(np.argmax(self.weights))]
        near = np.hypot(self.particles[:, 0] - best[0], self.particles[:, 1] - best[1]) < 0.5
        w = self.weights * near
        w = w / w.sum()
        x = float(w @ self.particles[:, 0])
        y = float(w @ self.particles[:, 1])
        th = math.atan2(
            float(w @ np.sin(self.particles[:, 2])), float(w @ np.cos(self.particles[:, 2]))
        )
        return Pose2D(x, y, th)

    def spread(self) -> float:
        """Weighted standard deviation of the particle positions (m): the belief's size."""
        mean = self.weights @ self.particles[:, :2]
        d2 = np.sum((self.particles[:, :2] - mean) ** 2, axis=1)
        return float(math.sqrt(float(self.weights @ d2)))


def wrap_angle_array(a: FloatArray) -> FloatArray:
    return np.asarray((a + math.pi) % (2.0 * math.pi) - math.pi)


def _usable_beams(scan: LaserScan, count: int) -> tuple[FloatArray, FloatArray]:
    """Up to ``count`` evenly spaced beams with a finite, in-range return."""
    step = max(1, len(scan.ranges) // count)
    ranges = scan.ranges[::step]
    angles = scan.angles()[::step]
    ok = np.isfinite(ranges) & (ranges > scan.range_min) & (ranges < scan.range_max)
    return ranges[ok], angles[ok]
