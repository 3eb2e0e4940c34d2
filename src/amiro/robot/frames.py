"""A driver's sensor data in amiro's frames (REP-105 names, laser at the base's centre).

amiro's navigation reads ``/scan`` as seen from the centre of the base, like the simulated
lidar.  A real laser sits elsewhere (forward, behind, flipped), so its points are moved
into the base frame and binned again by bearing from the centre.  Readings a driver marks
invalid (negative, NaN, infinite; Pepper's blind zones are -1) are dropped, and a bearing
no point falls in is NaN, "no measurement" in REP-117's terms.
"""

from __future__ import annotations

import math

import numpy as np

from amiro.core.messages import Header, LaserScan, Odometry
from amiro.robot.profile import Mount

LASER_FRAME = "laser"
ODOM_FRAME = "odom"
BASE_FRAME = "base_footprint"


def scan_in_base(scan: LaserScan, mount: Mount, stamp: float) -> LaserScan:
    """``scan`` re-expressed from the base's centre, in amiro's ``laser`` frame."""
    header = Header(stamp, LASER_FRAME)
    ranges = np.asarray(scan.ranges, dtype=np.float64)
    if mount.is_identity:
        return _with(scan, header, np.where(ranges >= 0.0, ranges, np.nan))
    angles = scan.angles()
    if mount.upside_down:
        angles = -angles
    ok = np.isfinite(ranges) & (ranges >= scan.range_min) & (ranges <= scan.range_max)
    c, s = math.cos(mount.yaw), math.sin(mount.yaw)
    lx, ly = ranges[ok] * np.cos(angles[ok]), ranges[ok] * np.sin(angles[ok])
    bx, by = mount.x + c * lx - s * ly, mount.y + s * lx + c * ly
    increment = abs(scan.angle_increment) or 2.0 * math.pi / max(len(ranges), 1)
    bins = max(1, round(2.0 * math.pi / increment))
    increment = 2.0 * math.pi / bins
    index = np.floor((np.arctan2(by, bx) + math.pi) / increment).astype(np.int64) % bins
    out = np.full(bins, np.inf)
    np.minimum.at(out, index, np.hypot(bx, by))
    out[np.isinf(out)] = np.nan
    reach = math.hypot(mount.x, mount.y)
    return LaserScan(
        header,
        -math.pi,
        math.pi - increment,
        increment,
        0.0,
        scan.scan_time,
        max(0.0, scan.range_min - reach),
        scan.range_max + reach,
        out,
    )


def _with(scan: LaserScan, header: Header, ranges: np.ndarray) -> LaserScan:
    return LaserScan(
        header,
        scan.angle_min,
        scan.angle_max,
        scan.angle_increment,
        scan.time_increment,
        scan.scan_time,
        scan.range_min,
        scan.range_max,
        ranges,
    )


def odometry_in_rep105(odom: Odometry, stamp: float) -> Odometry:
    """The driver's odometry under REP-105 names: ``odom`` -> ``base_footprint``."""
    return Odometry(Header(stamp, ODOM_FRAME), BASE_FRAME, odom.pose, odom.twist)
