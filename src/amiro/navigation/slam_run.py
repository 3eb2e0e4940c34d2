"""``amiro slam run``: SLAM over a CARMEN log, scored against the log's reference poses."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from amiro.core.gridmap import GridMap, map_pixels, save_map
from amiro.core.messages import Pose2D
from amiro.navigation.carmen import CarmenScan, read_carmen
from amiro.navigation.graph_slam import GraphSlam, GraphSlamParams, tracking_params
from amiro.navigation.metrics import ate_rmse, ate_similarity


@dataclass(frozen=True)
class SlamOutcome:
    poses: list[Pose2D]  # one per scan, map frame
    grid: GridMap
    seconds: float  # CPU time of the SLAM updates (a shared, loaded machine inflates wall time)
    slam: GraphSlam


def slam_over(
    scans: list[CarmenScan],
    odoms: list[Pose2D | None],
    fov_deg: float | None = None,
    max_range: float = 12.0,
    loop_closure: bool = True,
) -> SlamOutcome:
    """Graph SLAM over ``scans`` with ``odoms`` (one per scan) as the odometry."""
    slam = GraphSlam(GraphSlamParams(slam=tracking_params(max_range), loop_closure=loop_closure))
    fov = None if fov_deg is None else math.radians(fov_deg)
    t0 = time.process_time()
    for scan, odom in zip(scans, odoms, strict=True):
        slam.update(scan.ranges, scan.angles(fov), odom)
    slam.finish()
    elapsed = time.process_time() - t0
    return SlamOutcome(slam.trajectory(), slam.map(), elapsed, slam)


def odometry(scans: list[CarmenScan]) -> list[Pose2D | None]:
    """The scans' odometry; None for a log that carries none."""
    return [s.odom if s.odometry else None for s in scans]


def save_map_png(grid: GridMap, path: Path) -> None:
    """The map as a greyscale PNG (the PGM's pixels), to look at."""
    from PIL import Image

    Image.fromarray(np.ascontiguousarray(map_pixels(grid)), mode="L").save(path)


def run_slam(
    log: Path,
    out_dir: Path,
    fov_deg: float | None = None,
    max_range: float = 12.0,
    loop_closure: bool = True,
) -> dict[str, Any]:
    scans = read_carmen(log)
    run = slam_over(scans, odometry(scans), fov_deg, max_range, loop_closure)
    slam, poses = run.slam, run.poses
    out_dir.mkdir(parents=True, exist_ok=True)
    save_map(run.grid, out_dir / "map.yaml")
    save_map_png(run.grid, out_dir / "map.png")
    with (out_dir / "trajectory.csv").open("w", encoding="utf-8") as fh:
        fh.write("timestamp,x,y,theta\n")
        fh.writelines(
            f"{s.timestamp:.3f},{p.x:.4f},{p.y:.4f},{p.theta:.5f}\n"
            for s, p in zip(scans, poses, strict=True)
        )
    n = len(scans)
    result: dict[str, Any] = {"scans": n}
    refs = [s.reference for s in scans]
    if all(r is not None for r in refs):
        est = np.array([[p.x, p.y] for p in poses])
        ref = np.array([[r.x, r.y] for r in refs if r is not None])
        odo = np.array([[s.odom.x, s.odom.y] for s in scans])
        similarity_ate, scale = ate_similarity(est, ref)
        result |= {
            "ate_rmse_m": round(ate_rmse(est, ref), 4),
            "odom_ate_rmse_m": round(ate_rmse(odo, ref), 4),
            "similarity_ate_m": round(similarity_ate, 4),
            "scale_to_reference": round(scale, 5),
        }
    return result | {
        "ms_per_scan": round(1000.0 * run.seconds / n, 3),
        "backend_ms_per_scan": round(1000.0 * slam.backend_seconds / n, 3),
        "keyframes": len(slam.keyframes),
        "refused_matches": slam.frontend.refused,
        "loop_closures": slam.loop_closures,
        "loop_closure": loop_closure,
        "map": str(out_dir / "map.yaml"),
        "map_png": str(out_dir / "map.png"),
        "trajectory": str(out_dir / "trajectory.csv"),
    }
