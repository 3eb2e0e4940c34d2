"""CARMEN log files: the classic format of public 2D-lidar SLAM datasets.

Laser lines (the range readings, and a pose where the format has one):
``FLASER n r1..rn x y theta odom_x odom_y odom_theta timestamp host logger_timestamp``
``RAWLASER1..4 type start fov resolution max_range accuracy remission_mode n r1..rn
m e1..em timestamp host logger_timestamp`` (no pose),
``ROBOTLASER1`` as RAWLASER, then ``laser_x laser_y laser_theta robot_x robot_y robot_theta
tv rv forward_safety side_safety turn_axis timestamp host logger_timestamp``.
Odometry: ``ODOM x y theta tv rv accel timestamp host logger_timestamp``.

A laser line's pose is the reference (the dataset's corrected pose), used only to score.
Odometry comes from the ODOM lines when the log has them, else from the laser line's odom
fields.  The ODOM poses are chained as increments: gmapping's output logs re-anchor the
odometry to the corrected pose after every scan (an ODOM line right after the scan, equal
to its pose), and chaining the increments while skipping those jumps recovers the odometry
the robot really measured.

Time base: the scan's odometry is interpolated at its timestamp when the stamps are usable;
when they are missing, unsorted or printed with too few digits (``1.13486e+09`` is 10^4 s
coarse) the file order is the time base instead (the scan takes the odometry of the last
ODOM line before it, its timestamp becomes its index), and one warning says so.
"""

from __future__ import annotations

import gzip
import logging
import math
from dataclasses import dataclass
from pathlib import Path
from typing import IO

import numpy as np
import numpy.typing as npt

from amiro.core.config import ConfigError
from amiro.core.messages import Pose2D
from amiro.navigation.poses import between, compose

FloatArray = npt.NDArray[np.float64]

log = logging.getLogger(__name__)

LASERS = ("FLASER", "RAWLASER1", "RAWLASER2", "RAWLASER3", "RAWLASER4", "ROBOTLASER1")
# a stamp printed coarser than this cannot order scans 0.1 s apart
STAMP_RESOLUTION_S = 0.01
# an ODOM line this close to the scan before it is gmapping's re-anchoring, not a motion
ANCHOR_TOL = 1e-4


@dataclass(frozen=True)
class CarmenScan:
    timestamp: float
    ranges: FloatArray
    reference: Pose2D | None  # the log's (corrected) pose, None for RAWLASER
    odom: Pose2D
    start_angle: float | None = None  # first beam (rad), from the line when it says
    fov: float | None = None
    timed: bool = True  # False: the stamps were unusable, ``timestamp`` is the scan's index
    # False: the log carries no odometry (only gmapping's re-anchoring lines), ``odom`` is
    # the reference pose itself and must not be used as odometry
    odometry: bool = True

    def angles(self, fov: float | None = None) -> FloatArray:
        """Beam angles: the line's own geometry (RAWLASER, ROBOTLASER1); else ``fov``
        (centred) when given; else CARMEN's convention for FLASER lines."""
        n = len(self.ranges)
        if self.fov is not None and self.start_angle is not None:
            return _spread(self.start_angle, self.fov, n)
        if fov is not None:
            return _spread(-fov / 2.0, fov, n)
        return flaser_angles(n)


def flaser_angles(n: int) -> FloatArray:
    """CARMEN's FLASER beam geometry (``carmen_laser_get_angle_increment``): from -90
    degrees at 1, 0.5 or 0.25 degrees for 180/181, 360/361, 400/401 beams (a SICK's 180 or
    360 beams stop one step short of +90), else 180 degrees spread over the n beams.  Spread
    evenly, 180 beams would be 0.56 % too wide: 1 degree off at the last beam, 17 cm at 10 m."""
    step = {180: 1.0, 181: 1.0, 360: 0.5, 361: 0.5, 400: 0.25, 401: 0.25}.get(n)
    if step is None:
        return _spread(-math.pi / 2.0, math.pi, n)
    return -math.pi / 2.0 + math.radians(step) * np.arange(n, dtype=np.float64)


def _spread(start: float, fov: float, n: int) -> FloatArray:
    return np.linspace(start, start + fov, n) if n > 1 else np.full(1, start)


@dataclass(frozen=True)
class _Laser:
    line: int  # index among all ODOM and laser lines, the file-order time base
    stamp: float
    stamp_ok: bool
    ranges: FloatArray
    start: float | None
    fov: float | None
    reference: Pose2D | None
    odom: Pose2D | None


@dataclass(frozen=True)
class _Odom:
    line: int
    stamp: float
    stamp_ok: bool
    pose: Pose2D


def read_carmen(path: Path) -> list[CarmenScan]:
    """Every laser scan of a log (plain or .gz), each with its odometry; bad lines raise
    ConfigError."""
    if not path.is_file():
        raise ConfigError(f"{path}: no such file")
    with _open(path) as fh:
        lasers, odoms = _parse(path, fh)
    if not lasers:
        raise ConfigError(f"{path}: no laser lines ({', '.join(LASERS)})")
    motion = _chain(odoms, lasers)
    timed = _stamps_usable(lasers, motion)
    if not timed:
        log.warning(
            "%s: timestamps missing, unsorted or too coarse; using the file order as time base",
            path,
        )
    has_odometry = not _only_anchors(lasers, motion)
    if not has_odometry:
        log.warning("%s: no odometry increments between the scans; scans carry no odometry", path)
    scans = []
    for index, laser in enumerate(lasers):
        odom = _odometry_at(laser, motion, timed)
        stamp = laser.stamp if timed else float(index)
        scans.append(
            CarmenScan(
                stamp,
                laser.ranges,
                laser.reference,
                odom,
                laser.start,
                laser.fov,
                timed,
                has_odometry,
            )
        )
    return scans


def _open(path: Path) -> IO[str]:
    if path.suffix == ".gz":
        return gzip.open(path, "rt", encoding="utf-8", errors="replace")
    return path.open(encoding="utf-8", errors="replace")


def _parse(path: Path, fh: IO[str]) -> tuple[list[_Laser], list[_Odom]]:
    lasers: list[_Laser] = []
    odoms: list[_Odom] = []
    order = 0
    for number, line in enumerate(fh, 1):
        parts = line.split()
        if not parts or (parts[0] not in LASERS and parts[0] != "ODOM"):
            continue
        try:
            if parts[0] == "ODOM":
                stamp, ok = _stamp(parts[7])
                odoms.append(_Odom(order, stamp, ok, Pose2D(*(float(v) for v in parts[1:4]))))
            elif parts[0] == "FLASER":
                lasers.append(_flaser(order, parts))
            else:
                lasers.append(_rawlaser(order, parts))
        except (ValueError, IndexError):
            raise ConfigError(f"{path}:{number}: malformed {parts[0]} line") from None
        order += 1
    return lasers, odoms


def _stamp(token: str) -> tuple[float, bool]:
    """The value and whether it is a usable time: finite, not negative, and printed finely
    enough (``%g`` keeps 6 significant digits: 1.13486e+09 is only good to 10^4 s)."""
    value = float(token)
    if not math.isfinite(value) or value < 0.0:
        return value, False
    if value == 0.0:
        return value, True
    digits = sum(ch.isdigit() for ch in token.lower().partition("e")[0].lstrip("0."))
    resolution = 10.0 ** (math.floor(math.log10(value)) - max(6, digits) + 1)
    return value, resolution <= STAMP_RESOLUTION_S


def _flaser(order: int, parts: list[str]) -> _Laser:
    n = int(parts[1])
    if n <= 0 or len(parts) < 2 + n + 7:
        raise ValueError("short FLASER line")
    ranges = np.array([float(v) for v in parts[2 : 2 + n]])
    rest = [float(v) for v in parts[2 + n : 2 + n + 6]]
    stamp, ok = _stamp(parts[2 + n + 6])
    return _Laser(order, stamp, ok, ranges, None, None, Pose2D(*rest[0:3]), Pose2D(*rest[3:6]))


def _rawlaser(order: int, parts: list[str]) -> _Laser:
    start, fov = float(parts[2]), float(parts[3])
    n = int(parts[8])
    if n <= 0:
        raise ValueError("no readings")
    ranges = np.array([float(v) for v in parts[9 : 9 + n]])
    m = int(parts[9 + n])
    tail = parts[10 + n + m :]
    reference = odom = None
    if parts[0] == "ROBOTLASER1":
        robot = Pose2D(*(float(v) for v in tail[3:6]))
        reference, odom = robot, robot
        tail = tail[11:]
    stamp, ok = _stamp(tail[0])
    if len(ranges) != n:
        raise ValueError("short laser line")
    return _Laser(order, stamp, ok, ranges, start, fov, reference, odom)


@dataclass(frozen=True)
class _Motion:
    """The chained (raw) odometry after each ODOM line that moved it."""

    lines: list[int]
    stamps: list[float]
    stamps_ok: bool
    poses: list[Pose2D]


def _chain(odoms: list[_Odom], lasers: list[_Laser]) -> _Motion:
    """Chain the ODOM increments, skipping the re-anchoring line after each scan."""
    anchors = {}  # laser line index -> its reference pose
    for laser in lasers:
        if laser.reference is not None:
            anchors[laser.line] = laser.reference
    lines: list[int] = []
    stamps: list[float] = []
    poses: list[Pose2D] = []
    ok = True
    raw: Pose2D | None = None
    logged: Pose2D | None = None
    for odom in odoms:
        scan_ref = anchors.get(odom.line - 1)
        if logged is not None and scan_ref is not None and _same(odom.pose, scan_ref):
            logged = odom.pose  # re-anchored to the corrected pose: no motion
            continue
        raw = (
            odom.pose if raw is None or logged is None else compose(raw, between(logged, odom.pose))
        )
        logged = odom.pose
        lines.append(odom.line)
        stamps.append(odom.stamp)
        poses.append(raw)
        ok = ok and odom.stamp_ok
    return _Motion(lines, stamps, ok, poses)


def _only_anchors(lasers: list[_Laser], motion: _Motion) -> bool:
    """A gmapping log whose ODOM lines are (nearly) all re-anchoring lines: increments
    between fewer than a tenth of its scan pairs (Orebro: 18 lines for 237 scans, 18 % of
    the path).  Logs without ODOM lines take the laser lines' own odometry fields."""
    anchored = sum(laser.reference is not None for laser in lasers)
    if not motion.lines or anchored < len(lasers):
        return False
    return len(motion.lines) < 0.1 * len(lasers)


def _same(a: Pose2D, b: Pose2D) -> bool:
    d_theta = math.remainder(a.theta - b.theta, math.tau)
    return abs(a.x - b.x) <= ANCHOR_TOL and abs(a.y - b.y) <= ANCHOR_TOL and abs(d_theta) <= 1e-3


def _stamps_usable(lasers: list[_Laser], motion: _Motion) -> bool:
    scan_stamps = np.array([laser.stamp for laser in lasers])
    if not all(laser.stamp_ok for laser in lasers) or np.any(np.diff(scan_stamps) <= 0.0):
        return False
    return motion.stamps_ok and not np.any(np.diff(np.array(motion.stamps)) < 0.0)


def _odometry_at(laser: _Laser, motion: _Motion, timed: bool) -> Pose2D:
    """The chained odometry at the scan: interpolated at its stamp, else the last ODOM line
    before it in the file; the line's own odom fields when the log has no ODOM."""
    if not motion.poses:
        return laser.odom if laser.odom is not None else Pose2D()
    if timed:
        return _interpolate(motion, laser.stamp)
    i = int(np.searchsorted(np.array(motion.lines), laser.line)) - 1
    return motion.poses[max(0, i)]


def _interpolate(motion: _Motion, stamp: float) -> Pose2D:
    t = np.array(motion.stamps)
    i = int(np.searchsorted(t, stamp, side="right"))
    if i == 0:
        return motion.poses[0]
    if i == len(t):
        return motion.poses[-1]
    a, b = motion.poses[i - 1], motion.poses[i]
    span = t[i] - t[i - 1]
    f = 0.0 if span <= 0.0 else (stamp - t[i - 1]) / span
    d = between(a, b)
    return compose(a, Pose2D(f * d.x, f * d.y, f * d.theta))


def flaser_line(stamp: float, ranges: FloatArray, reference: Pose2D, odom: Pose2D) -> str:
    vals = " ".join(f"{r:.3f}" for r in ranges)
    poses = " ".join(
        f"{v:.5f}" for v in (reference.x, reference.y, reference.theta, odom.x, odom.y, odom.theta)
    )
    return f"FLASER {len(ranges)} {vals} {poses} {stamp:.3f} amiro-sim {stamp:.3f}"


def odom_line(stamp: float, odom: Pose2D, tv: float, rv: float) -> str:
    pose = f"{odom.x:.5f} {odom.y:.5f} {odom.theta:.5f}"
    return f"ODOM {pose} {tv:.3f} {rv:.3f} 0 {stamp:.3f} amiro-sim {stamp:.3f}"
