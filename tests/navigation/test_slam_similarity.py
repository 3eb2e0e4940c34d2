"""The similarity-aligned ATE separates a uniformly scaled map from a distorted one."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from amiro.navigation.metrics import ate_rmse, ate_similarity

FloatArray = npt.NDArray[np.float64]


def _loop(rng: np.random.Generator) -> FloatArray:
    """A 20 x 15 m rectangle walked every 0.2 m, a little jitter on top."""
    side = np.arange(0.0, 1.0, 0.01)
    xy = np.concatenate(
        (
            np.column_stack((20 * side, 0 * side)),
            np.column_stack((20 + 0 * side, 15 * side)),
            np.column_stack((20 - 20 * side, 15 + 0 * side)),
            np.column_stack((0 * side, 15 - 15 * side)),
        )
    )
    return xy + 0.005 * rng.standard_normal(xy.shape)


def _rigid(xy: FloatArray, angle: float, shift: tuple[float, float]) -> FloatArray:
    c, s = np.cos(angle), np.sin(angle)
    out: FloatArray = xy @ np.array([[c, s], [-s, c]]) + np.asarray(shift)
    return out


def test_a_shrunk_map_is_only_a_scale_error() -> None:
    ref = _loop(np.random.default_rng(0))
    est = _rigid(0.992 * ref, 0.4, (3.0, -2.0))  # 0.8 % too short, moved and turned
    rigid = ate_rmse(est, ref)
    similar, scale = ate_similarity(est, ref)
    assert rigid > 0.03  # 0.8 % of a ~7 m radius
    assert similar < 1e-6
    assert abs(scale - 1.0 / 0.992) < 1e-6


def test_a_bent_map_keeps_its_error_after_scaling() -> None:
    ref = _loop(np.random.default_rng(1))
    est = ref.copy()
    est[ref[:, 0] > 10.0, 1] += 0.2  # one half shifted: not a similarity
    similar, scale = ate_similarity(_rigid(est, -1.0, (5.0, 5.0)), ref)
    assert similar > 0.05
    assert abs(scale - 1.0) < 0.01
    assert abs(similar - ate_rmse(est, ref)) < 0.02
