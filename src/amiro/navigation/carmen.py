"""CARMEN log files: the classic format of public 2D-lidar SLAM datasets.

``FLASER n r1..rn x y theta odom_x odom_y odom_theta timestamp host logger_timestamp``
``ODOM x y theta tv rv accel timestamp host logger_timestamp``

A FLASER's first pose triple is the reference (the dataset's corrected pose), used only to
score; odometry comes from ODOM lines when the log has them (the latest one at or before the
scan), else from the FLASER's own odom fields.  Beams span ``fov`` (180 degrees, as the
front lasers of those datasets) from right to left.
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from amiro.core.config import ConfigError
from amiro.core.messages import Pose2D

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class CarmenScan:
    timestamp: float
    ranges: FloatArray
    reference: Pose2D
    odom: Pose2D

    def angles(self, fov: float = math.pi) -> FloatArray:
        n = len(self.ranges)
        return np.linspace(-fov / 2.0, fov / 2.0, n) if n > 1 else np.zeros(1)


def read_carmen(path: Path) -> list[CarmenScan]:
    """All FLASER scans of a log, each with its odometry; bad lines raise ConfigError."""
    if not path.is_file():
        raise ConfigError(f"{path}: no such file")
    lasers: list[tuple[float, FloatArray, Pose2D, Pose2D]] = []
    odom_t: list[float] = []
    odom_p: list[Pose2D] = []
    with path.open(encoding="utf-8", errors="replace") as fh:
        for number, line in enumerate(fh, 1):
            parts = line.split()
            if not parts or parts[0] not in ("FLASER", "ODOM"):
                continue
            try:
                if parts[0] == "FLASER":
                    lasers.append(_parse_flaser(parts))
                else:
                    x, y, th = (float(v) for v in parts[1:4])
                    odom_t.append(float(parts[7]))
                    odom_p.append(Pose2D(x, y, th))
            except (ValueError, IndexError):
                raise ConfigError(f"{path}:{number}: malformed {parts[0]} line") from None
    if not lasers:
        raise ConfigError(f"{path}: no FLASER lines")
    scans = []
    for stamp, ranges, ref, flaser_odom in lasers:
        odom = flaser_odom
        if odom_t:
            i = max(0, bisect.bisect_right(odom_t, stamp) - 1)
            odom = odom_p[i]
        scans.append(CarmenScan(stamp, ranges, ref, odom))
    return scans


def _parse_flaser(parts: list[str]) -> tuple[float, FloatArray, Pose2D, Pose2D]:
    n = int(parts[1])
    if n <= 0 or len(parts) < 2 + n + 7:
        raise ValueError("short FLASER line")
    ranges = np.array([float(v) for v in parts[2 : 2 + n]])
    rest = [float(v) for v in parts[2 + n : 2 + n + 7]]
    return rest[6], ranges, Pose2D(*rest[0:3]), Pose2D(*rest[3:6])


def flaser_line(stamp: float, ranges: FloatArray, reference: Pose2D, odom: Pose2D) -> str:
    vals = " ".join(f"{r:.3f}" for r in ranges)
    poses = " ".join(
        f"{v:.5f}" for v in (reference.x, reference.y, reference.theta, odom.x, odom.y, odom.theta)
    )
    return f"FLASER {len(ranges)} {vals} {poses} {stamp:.3f} amiro-sim {stamp:.3f}"


def odom_line(stamp: float, odom: Pose2D, tv: float, rv: float) -> str:
    pose = f"{odom.x:.5f} {odom.y:.5f} {odom.theta:.5f}"
    return f"ODOM {pose} {tv:.3f} {rv:.3f} 0 {stamp:.3f} amiro-sim {stamp:.3f}"
