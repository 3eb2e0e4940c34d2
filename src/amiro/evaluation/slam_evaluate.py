"""``amiro slam evaluate``: SLAM over every CARMEN log of a folder, scored against its reference.

Each log runs twice: (a) with the odometry the robot really measured (recovered by the
reader), (b) with Pepper-like drift instead: the reference trajectory's scan-to-scan motion
fed through the simulator's drifting odometry (``amiro.sim.base.Odometry``, seeded).

Scores, per run: ATE RMSE after the rigid SE(2) alignment (``metrics.ate_rmse``); the relation
error of Kümmerle et al. 2009 over relations derived from the reference trajectory: for every
scan i, the pair (i, j) with j the first scan at least ``RELATION_M`` (1 m) of reference path
further, so a relation spans one scan on the 1 m-spaced logs and ~10 on 0.1 m ones; its
translation (m) and rotation (deg) parts, mean and standard deviation; the SLAM's wall time per
scan beside the log's scan rate (scans per second of recording, when its stamps are times).
"""

from __future__ import annotations

import itertools
import math
import statistics
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from amiro.core.gridmap import GridMap
from amiro.core.messages import Pose2D
from amiro.navigation.carmen import CarmenScan, read_carmen
from amiro.navigation.metrics import align, ate_rmse
from amiro.navigation.poses import between
from amiro.navigation.slam_run import odometry, save_map_png, slam_over
from amiro.sim.base import Odometry

FloatArray = npt.NDArray[np.float64]

RELATION_M = 1.0
DRIFTS = ("real", "pepper")


@dataclass(frozen=True)
class RelationError:
    trans_mean: float
    trans_std: float
    rot_mean_deg: float
    rot_std_deg: float


def relation_pairs(reference: list[Pose2D], spacing: float = RELATION_M) -> list[tuple[int, int]]:
    """(i, j): j the first scan at least ``spacing`` of reference path after i."""
    steps = [a.distance_to(b) for a, b in itertools.pairwise(reference)]
    path = np.concatenate(([0.0], np.cumsum(steps)))
    js = np.searchsorted(path, path + spacing, side="left")
    return [(i, int(j)) for i, j in enumerate(js) if j < len(reference)]


def relation_error(
    estimate: list[Pose2D], reference: list[Pose2D], pairs: list[tuple[int, int]]
) -> RelationError:
    """Kümmerle et al. 2009: the estimated relative motion of each pair against the
    reference's, ``delta_ref^-1 * delta_est``, split into translation and rotation."""
    trans, rot = [], []
    for i, j in pairs:
        err = between(between(reference[i], reference[j]), between(estimate[i], estimate[j]))
        trans.append(math.hypot(err.x, err.y))
        rot.append(abs(math.degrees(math.remainder(err.theta, math.tau))))
    if not trans:
        return RelationError(0.0, 0.0, 0.0, 0.0)
    return RelationError(
        statistics.fmean(trans),
        statistics.pstdev(trans),
        statistics.fmean(rot),
        statistics.pstdev(rot),
    )


def pepper_odometry(reference: list[Pose2D], seed: int) -> list[Pose2D]:
    """The reference motion as Pepper's drifting odometry would have measured it."""
    odometry = Odometry(np.random.default_rng(seed))
    out = [odometry.pose]
    for a, b in itertools.pairwise(reference):
        d = between(a, b)
        out.append(odometry.update(d.x, d.y, d.theta))
    return out


def scan_rate(scans: list[CarmenScan]) -> float | None:
    """Scans per second of recording; None when the log's stamps are not times."""
    span = scans[-1].timestamp - scans[0].timestamp
    if not scans[0].timed or span <= 0.0:
        return None
    return (len(scans) - 1) / span


def evaluate_log(
    path: Path, out_dir: Path | None, drifts: tuple[str, ...], seed: int = 0
) -> list[dict[str, Any]]:
    """One row per drift for the log at ``path``; a plot per row in ``out_dir``."""
    scans = read_carmen(path)
    reference = [s.reference for s in scans]
    if any(r is None for r in reference):
        raise ValueError(f"{path}: scans without a reference pose cannot be scored")
    ref = [r for r in reference if r is not None]
    ref_xy = _xy(ref)
    pairs = relation_pairs(ref)
    rate = scan_rate(scans)
    name = path.name.removesuffix(".gz").removesuffix(".log")
    rows = []
    for drift in drifts:
        odoms = [s.odom for s in scans] if drift == "real" else pepper_odometry(ref, seed)
        print(f"slam evaluate: {name} ({drift} odometry, {len(scans)} scans)", file=sys.stderr)
        run = slam_over(scans, odometry(scans) if drift == "real" else list(odoms))
        rel = relation_error(run.poses, ref, pairs)
        row = {
            "log": name,
            "odometry": drift,
            "scans": len(scans),
            "ate_rmse_m": round(ate_rmse(_xy(run.poses), ref_xy), 4),
            "odom_ate_rmse_m": round(ate_rmse(_xy(odoms), ref_xy), 4),
            "rel_trans_m": round(rel.trans_mean, 4),
            "rel_trans_std_m": round(rel.trans_std, 4),
            "rel_rot_deg": round(rel.rot_mean_deg, 3),
            "rel_rot_std_deg": round(rel.rot_std_deg, 3),
            "relations": len(pairs),
            "ms_per_scan": round(1000.0 * run.seconds / len(scans), 2),
            "log_scans_per_s": None if rate is None else round(rate, 2),
            "loop_closures": run.slam.loop_closures,
        }
        if out_dir is not None:
            out_dir.mkdir(parents=True, exist_ok=True)
            plot = out_dir / f"{name}-{drift}.png"
            _plot(plot, run.poses, ref_xy, run.grid, row)
            save_map_png(run.grid, out_dir / f"{name}-{drift}-map.png")
            row["plot"] = str(plot)
        rows.append(row)
    return rows


def evaluate_dir(
    folder: Path, out_dir: Path | None, drifts: tuple[str, ...], seed: int = 0
) -> dict[str, Any]:
    logs = sorted(p for p in folder.iterdir() if p.name.endswith((".log", ".log.gz")))
    rows = []
    for k, path in enumerate(logs, 1):
        print(f"slam evaluate: log {k}/{len(logs)}", file=sys.stderr)
        rows.extend(evaluate_log(path, out_dir, drifts, seed))
    summary = {}
    for drift in drifts:
        ates = [r["ate_rmse_m"] for r in rows if r["odometry"] == drift]
        if ates:
            summary[drift] = {
                "median_ate_m": round(statistics.median(ates), 4),
                "worst_ate_m": max(ates),
                "mean_rel_trans_m": round(
                    statistics.fmean(r["rel_trans_m"] for r in rows if r["odometry"] == drift), 4
                ),
            }
    return {"logs": rows, "summary": summary}


def format_table(result: dict[str, Any]) -> str:
    head = (
        f"{'log':<28} {'odom':<6} {'scans':>5} {'ATE m':>7} {'odomATE':>8} "
        f"{'rel m (mean±std)':>17} {'rel deg':>13} {'ms/scan':>8} {'scan/s':>7} {'loops':>5}"
    )
    lines = [head]
    for r in result["logs"]:
        rate = "-" if r["log_scans_per_s"] is None else f"{r['log_scans_per_s']:.2f}"
        lines.append(
            f"{r['log']:<28} {r['odometry']:<6} {r['scans']:>5} {r['ate_rmse_m']:>7.3f} "
            f"{r['odom_ate_rmse_m']:>8.2f} "
            f"{r['rel_trans_m']:>8.3f}±{r['rel_trans_std_m']:<8.3f} "
            f"{r['rel_rot_deg']:>6.2f}±{r['rel_rot_std_deg']:<6.2f} "
            f"{r['ms_per_scan']:>8.1f} {rate:>7} {r['loop_closures']:>5}"
        )
    for drift, s in result["summary"].items():
        lines.append(
            f"{drift}: median ATE {s['median_ate_m']:.3f} m, worst {s['worst_ate_m']:.3f} m, "
            f"mean relation error {s['mean_rel_trans_m']:.3f} m"
        )
    return "\n".join(lines)


def _xy(poses: list[Pose2D]) -> FloatArray:
    return np.array([[p.x, p.y] for p in poses])


def _plot(
    path: Path, poses: list[Pose2D], ref_xy: FloatArray, grid: GridMap, row: dict[str, Any]
) -> None:
    """Left: the estimate aligned onto the reference; right: the map with the estimate."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    est = _xy(poses)
    fig, (ax_t, ax_m) = plt.subplots(1, 2, figsize=(13, 6.5))
    ax_t.plot(ref_xy[:, 0], ref_xy[:, 1], "k-", lw=1.0, label="reference (gmapping)")
    aligned = align(est, ref_xy)
    ax_t.plot(aligned[:, 0], aligned[:, 1], "r-", lw=0.8, label="SLAM")
    ax_t.set_aspect("equal")
    ax_t.legend(loc="best", fontsize=8)
    ax_t.set_title(
        f"{row['log']} ({row['odometry']} odometry): ATE {row['ate_rmse_m']:.3f} m, "
        f"relation {row['rel_trans_m']:.3f} m",
        fontsize=9,
    )
    img = np.where(grid.data < 0, 0.5, 1.0 - grid.data / 100.0)
    x0, y0 = grid.origin[0], grid.origin[1]
    h, w = grid.data.shape
    extent = (x0, x0 + w * grid.resolution, y0, y0 + h * grid.resolution)
    ax_m.imshow(img, cmap="gray", origin="lower", extent=extent, vmin=0.0, vmax=1.0)
    ax_m.plot(est[:, 0], est[:, 1], "r-", lw=0.5)
    ax_m.set_title("map and SLAM trajectory", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
