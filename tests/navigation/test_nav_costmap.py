"""Costmap: inflation, soft cost, lidar marking, clearance and the way out."""

from __future__ import annotations

import math

import numpy as np
import pytest

from amiro.core.messages import Header, LaserScan, Pose2D
from amiro.navigation.costmap import Costmap, GridFrame, downsample

RES = 0.1


def _costmap(static: np.ndarray | None = None) -> Costmap:
    """40 x 40 cells of 0.1 m, origin (-0.5, -0.5)."""
    if static is None:
        static = np.zeros((40, 40), dtype=bool)
    frame = GridFrame(RES, -0.5, -0.5, *static.shape)
    # inscribed radius 0.35 m = 3.5 cells: no cell centre lies exactly on it
    return Costmap(static, frame, robot_radius=0.25, safety_margin=0.1)


def _grid() -> np.ndarray:
    return np.zeros((40, 40), dtype=bool)


def _scan(angles_rel: list[float], ranges: list[float], range_min: float = 0.15) -> LaserScan:
    """A scan whose beam i points at angle_min + i * increment; angles must be evenly spaced."""
    inc = angles_rel[1] - angles_rel[0] if len(angles_rel) > 1 else 0.0
    for i, a in enumerate(angles_rel):
        assert a == pytest.approx(angles_rel[0] + i * inc)
    return LaserScan(
        header=Header(0.0, "laser"),
        angle_min=angles_rel[0],
        angle_max=angles_rel[-1],
        angle_increment=inc,
        time_increment=0.0,
        scan_time=0.1,
        range_min=range_min,
        range_max=12.0,
        ranges=np.asarray(ranges, dtype=np.float64),
    )


def test_frame_round_trip() -> None:
    frame = GridFrame(RES, -0.5, 0.25, 30, 20)
    assert frame.to_cell(-0.45, 0.3) == (0, 0)
    assert frame.to_cell(1.04, 2.06) == (18, 15)
    assert frame.to_world(18, 15) == pytest.approx((1.05, 2.1))
    assert frame.inside(29, 19) and not frame.inside(30, 0) and not frame.inside(0, -1)


def test_inflation_radius_is_robot_radius_plus_margin() -> None:
    static = _grid()
    static[20, 20] = True
    cm = _costmap(static)
    rr, cc = np.mgrid[0:40, 0:40]
    d2 = (rr - 20) ** 2 + (cc - 20) ** 2
    within = d2 * RES**2 < cm.inscribed**2
    assert cm.inscribed == pytest.approx(0.35)
    np.testing.assert_array_equal(cm.lethal, within)
    # spot checks on both sides of the 0.35 m boundary
    assert cm.lethal[20, 23] and not cm.lethal[20, 24]  # 0.30 m vs 0.40 m
    assert cm.lethal[22, 22] and not cm.lethal[23, 22]  # 0.28 m vs 0.36 m


def test_soft_cost_is_one_inside_and_decays_with_distance() -> None:
    static = _grid()
    static[:, :3] = True  # a wall along the left edge
    cm = _costmap(static)
    row = cm.cost[20]
    lethal = cm.lethal[20]
    assert np.all(row[lethal] == pytest.approx(1.0))
    free = row[~lethal]
    assert free.size > 20
    assert np.all(np.diff(free) < 0), "cost must strictly decrease away from the wall"
    assert free[0] < 1.0 and free[-1] < 0.01
    # the documented exponential decay from the inscribed radius
    d = cm.clearance[20, 30]
    assert cm.cost[20, 30] == pytest.approx(math.exp(-(d - cm.inscribed) / cm.decay_m))


def test_mark_scan_marks_hits_at_the_right_cells() -> None:
    cm = _costmap()
    pose = Pose2D(1.03, 1.07, math.pi / 2)  # facing +y
    # relative angles -90, 0, 90, 180 deg -> map directions +x, +y, -x, -y
    scan = _scan(
        [-math.pi / 2, 0.0, math.pi / 2, math.pi],
        [1.0, 2.0, math.inf, 0.05],  # +x hit, +y hit, no return, below range_min
    )
    assert cm.mark_scan(scan, pose) == 2
    marked = {tuple(int(v) for v in rc) for rc in np.argwhere(cm.observed)}
    # (2.03, 1.07) and (1.03, 3.07) with origin (-0.5, -0.5) at 0.1 m
    assert marked == {(15, 25), (35, 15)}
    assert cm.frame.to_cell(2.03, 1.07) == (15, 25)
    # the new obstacle is inflated into the lethal layer
    assert cm.lethal[15, 25] and cm.lethal[15, 22] and not cm.lethal[15, 21]
    # the same scan again marks nothing new
    assert cm.mark_scan(scan, pose) == 0


def test_mark_scan_ignores_far_hits_and_known_obstacles() -> None:
    static = _grid()
    static[15, 25] = True
    cm = _costmap(static)
    pose = Pose2D(1.03, 1.07, 0.0)
    scan = _scan([0.0, math.pi / 2], [1.0, 4.5])  # known wall ahead, 4.5 m > max_range 4
    assert cm.mark_scan(scan, pose) == 0
    assert not cm.observed.any()
    # hits outside the map are dropped, not wrapped around
    assert cm.mark_scan(_scan([math.pi], [2.0]), pose) == 0
    assert not cm.observed.any()


def test_mark_scan_counts_cells_not_beams() -> None:
    cm = _costmap()
    n = 9
    angles = list(np.linspace(-0.02, 0.02, n))
    scan = _scan(angles, [1.0] * n)  # nine beams ending within 4 cm: one cell
    assert cm.mark_scan(scan, Pose2D(1.05, 1.05, 0.0)) == int(cm.observed.sum()) == 1


def test_range_noise_in_front_of_a_mapped_wall_is_not_an_obstacle() -> None:
    static = _grid()
    static[:, 30] = True  # a wall at x in [2.5, 2.6)
    cm = _costmap(static)
    pose = Pose2D(0.53, 1.07, 0.0)
    # wall returns 0.03 and 0.07 m short of the wall face (x = 2.5), in the cell in front
    # of it: range noise, not obstacles
    assert cm.mark_scan(_scan([0.0, 0.1], [1.94, 1.90 / math.cos(0.1)]), pose) == 0
    assert not cm.observed.any()
    # something 0.4 m in front of the wall is new
    assert cm.mark_scan(_scan([0.0], [1.57]), pose) == 1
    assert cm.observed[15, 26]


def test_clear_observed_restores_the_static_costmap() -> None:
    static = _grid()
    static[5, 5] = True
    cm = _costmap(static)
    static_lethal = cm.lethal.copy()
    assert cm.mark_scan(_scan([0.0], [1.0]), Pose2D(1.03, 1.07, 0.0)) == 1
    assert cm.lethal.sum() > static_lethal.sum()
    cm.clear_observed()
    assert not cm.observed.any()
    np.testing.assert_array_equal(cm.lethal, static_lethal)
    assert cm.static[5, 5]


def test_clearance_and_the_way_out_point_away_from_walls() -> None:
    static = _grid()
    static[:, :3] = True  # left wall, cells x in [-0.5, -0.2)
    cm = _costmap(static)
    # 1 m right of the wall's last cell centre (x = -0.25)
    assert cm.clearance_at(0.77, 1.53) == pytest.approx(1.0)
    gx, gy = cm.away_from_obstacles(0.07, 1.53)
    assert gx == pytest.approx(1.0, abs=1e-6) and gy == pytest.approx(0.0, abs=1e-6)
    top = _grid()
    top[37:, :] = True  # top wall (high y)
    cm = _costmap(top)
    gx, gy = cm.away_from_obstacles(1.53, 2.93)
    assert gx == pytest.approx(0.0, abs=1e-6) and gy == pytest.approx(-1.0, abs=1e-6)
    assert cm.clearance_at(1.53, 2.93) < cm.clearance_at(1.53, 2.03)
    # in a corner, 5 cells from both walls: the way out is diagonal, away from both
    cm = _costmap(static | top)
    assert cm.frame.to_cell(0.27, 2.77) == (32, 7)
    gx, gy = cm.away_from_obstacles(0.27, 2.77)
    assert (gx, gy) == pytest.approx((math.sqrt(0.5), -math.sqrt(0.5)))
    # outside the map: no clearance, no direction
    assert cm.clearance_at(-5.0, 0.0) == 0.0
    assert cm.away_from_obstacles(-5.0, 0.0) == (0.0, 0.0)


def test_downsample_keeps_every_obstacle() -> None:
    fine = np.zeros((7, 9), dtype=bool)
    fine[0, 0] = fine[6, 8] = fine[3, 4] = True
    coarse = downsample(fine, 2)
    assert coarse.shape == (4, 5)
    assert coarse[0, 0] and coarse[3, 4] and coarse[1, 2]
    assert int(coarse.sum()) == 3
    assert downsample(fine, 1) is fine
