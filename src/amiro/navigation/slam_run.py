"""``amiro slam run``: SLAM over a CARMEN log, scored against the log's reference poses."""

from __future__ import annotations

import math
import time
from pathlib import Path
from typing import Any

import numpy as np

from amiro.core.gridmap import save_map
from amiro.navigation.carmen import read_carmen
from amiro.navigation.metrics import ate_rmse
from amiro.navigation.slam import HectorSlam, SlamParams


def run_slam(
    log: Path, out_dir: Path, fov_deg: float = 180.0, max_range: float = 12.0
) -> dict[str, Any]:
    scans = read_carmen(log)
    slam = HectorSlam(SlamParams(max_range=max_range))
    fov = math.radians(fov_deg)
    rows = []
    t0 = time.perf_counter()  # wall time only to measure speed
    for scan in scans:
        pose = slam.update(scan.ranges, scan.angles(fov), scan.odom)
        rows.append((scan.timestamp, pose.x, pose.y, pose.theta))
    elapsed = time.perf_counter() - t0
    out_dir.mkdir(parents=True, exist_ok=True)
    save_map(slam.map(), out_dir / "map.yaml")
    with (out_dir / "trajectory.csv").open("w", encoding="utf-8") as fh:
        fh.write("timestamp,x,y,theta\n")
        fh.writelines(f"{t:.3f},{x:.4f},{y:.4f},{th:.5f}\n" for t, x, y, th in rows)
    est = np.array([[r[1], r[2]] for r in rows])
    ref = np.array([[s.reference.x, s.reference.y] for s in scans])
    odo = np.array([[s.odom.x, s.odom.y] for s in scans])
    return {
        "scans": len(scans),
        "ate_rmse_m": round(ate_rmse(est, ref), 4),
        "odom_ate_rmse_m": round(ate_rmse(odo, ref), 4),
        "ms_per_scan": round(1000.0 * elapsed / len(scans), 3),
        "map": str(out_dir / "map.yaml"),
        "trajectory": str(out_dir / "trajectory.csv"),
    }
