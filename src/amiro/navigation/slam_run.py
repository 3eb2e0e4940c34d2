"""``amiro slam run``: SLAM over a CARMEN log, scored against the log's reference poses."""

from __future__ import annotations

import math
import time
from pathlib import Path
from typing import Any

import numpy as np

from amiro.core.gridmap import save_map
from amiro.navigation.carmen import read_carmen
from amiro.navigation.graph_slam import GraphSlam, GraphSlamParams, tracking_params
from amiro.navigation.metrics import ate_rmse, ate_similarity


def run_slam(
    log: Path,
    out_dir: Path,
    fov_deg: float = 180.0,
    max_range: float = 12.0,
    loop_closure: bool = True,
) -> dict[str, Any]:
    scans = read_carmen(log)
    slam = GraphSlam(GraphSlamParams(slam=tracking_params(max_range), loop_closure=loop_closure))
    fov = math.radians(fov_deg)
    t0 = time.perf_counter()  # wall time only to measure speed
    for scan in scans:
        slam.update(scan.ranges, scan.angles(fov), scan.odom)
    slam.finish()
    elapsed = time.perf_counter() - t0
    poses = slam.trajectory()
    out_dir.mkdir(parents=True, exist_ok=True)
    save_map(slam.map(), out_dir / "map.yaml")
    with (out_dir / "trajectory.csv").open("w", encoding="utf-8") as fh:
        fh.write("timestamp,x,y,theta\n")
        fh.writelines(
            f"{s.timestamp:.3f},{p.x:.4f},{p.y:.4f},{p.theta:.5f}\n"
            for s, p in zip(scans, poses, strict=True)
        )
    est = np.array([[p.x, p.y] for p in poses])
    ref = np.array([[s.reference.x, s.reference.y] for s in scans])
    odo = np.array([[s.odom.x, s.odom.y] for s in scans])
    n = len(scans)
    similarity_ate, scale = ate_similarity(est, ref)
    return {
        "scans": n,
        "ate_rmse_m": round(ate_rmse(est, ref), 4),
        "odom_ate_rmse_m": round(ate_rmse(odo, ref), 4),
        "similarity_ate_m": round(similarity_ate, 4),
        "scale_to_reference": round(scale, 5),
        "ms_per_scan": round(1000.0 * elapsed / n, 3),
        "backend_ms_per_scan": round(1000.0 * slam.backend_seconds / n, 3),
        "keyframes": len(slam.keyframes),
        "refused_matches": slam.frontend.refused,
        "loop_closures": slam.loop_closures,
        "loop_closure": loop_closure,
        "map": str(out_dir / "map.yaml"),
        "trajectory": str(out_dir / "trajectory.csv"),
    }
