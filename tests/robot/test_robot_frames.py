"""A driver's scan and odometry in amiro's frames."""

from __future__ import annotations

import math

import numpy as np
import pytest

from amiro.core.messages import Header, LaserScan, Odometry, Pose, Twist
from amiro.robot.frames import odometry_in_rep105, scan_in_base
from amiro.robot.profile import Mount


def _scan(ranges: list[float], frame: str = "base_scan") -> LaserScan:
    n = len(ranges)
    inc = 2 * math.pi / n
    return LaserScan(
        Header(5.0, frame), -math.pi, math.pi - inc, inc, 0.0, 0.1, 0.1, 10.0, np.array(ranges)
    )


def _bearing_range(scan: LaserScan) -> list[tuple[float, float]]:
    ok = np.isfinite(scan.ranges)
    return list(zip(scan.angles()[ok], scan.ranges[ok], strict=True))


def test_identity_mount_renames_the_frame_and_marks_invalid_readings() -> None:
    scan = scan_in_base(_scan([1.0, -1.0, 2.0, 3.0]), Mount(), stamp=9.0)
    assert scan.header == Header(9.0, "laser")
    assert np.isnan(scan.ranges[1]) and scan.ranges[2] == 2.0


def test_a_forward_laser_sees_a_wall_closer_from_the_laser_than_from_the_centre() -> None:
    ranges = [math.inf] * 360
    ranges[180] = 1.0  # straight ahead of the laser (bearing 0)
    scan = scan_in_base(_scan(ranges), Mount(x=0.2), stamp=1.0)
    [(bearing, dist)] = _bearing_range(scan)
    assert dist == pytest.approx(1.2)
    assert abs(bearing) < 2 * math.pi / 360 + 1e-9


def test_an_upside_down_laser_mirrors_left_and_right() -> None:
    ranges = [math.inf] * 360
    ranges[270] = 2.0  # 90 deg to the laser's left
    scan = scan_in_base(_scan(ranges), Mount(upside_down=True, y=0.0, x=0.0, yaw=0.0), 1.0)
    [(bearing, dist)] = _bearing_range(scan)
    assert dist == pytest.approx(2.0)
    assert bearing == pytest.approx(-math.pi / 2, abs=2 * math.pi / 360)


def test_odometry_gets_rep105_names_and_the_runtime_stamp() -> None:
    odom = Odometry(Header(123.0, "odom"), "base_link", Pose(), Twist.planar(0.1, 0, 0))
    out = odometry_in_rep105(odom, 4.0)
    assert (out.header.frame_id, out.child_frame_id, out.header.stamp) == (
        "odom",
        "base_footprint",
        4.0,
    )
    assert out.twist == odom.twist
