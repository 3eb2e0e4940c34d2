"""``amiro nav experiments``: the paper's section-4.3 navigation experiments in the simulator.

Five experiments, each run several times with different seeds (odometry drift, lidar noise,
particle filter): in a 5 m x 2.5 m area, forward movement, one obstacle, a slalom between two
obstacles (obstacles mapped with the area, as the robot explored it first); then a 13 m
hallway, through a door, left turn, 4 m more, without and with boxes that are not in the map
(the lidar finds them and the planner re-plans).  The robot navigates with the default stack
(AMCL, A*, DWA); as in the paper, the trajectory is the pose estimated by SLAM running beside
it, and DTW compares it with the plan the robot followed.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from amiro.core import names
from amiro.core.bus import GoalHandle
from amiro.core.clock import SimClock
from amiro.core.gridmap import OCCUPIED
from amiro.core.messages import Path as PathMsg
from amiro.core.messages import Pose2D
from amiro.core.runtime import Runtime
from amiro.home.world import World
from amiro.navigation.config import NavigationConfig
from amiro.navigation.metrics import dtw, path_length, resample
from amiro.navigation.move_to import MoveToFeedback, MoveToGoal, MoveToResult
from amiro.navigation.slam import SlamParams
from amiro.navigation.slam_node import SlamNode
from amiro.navigation.stack import build_navigation
from amiro.robot.velocity_mux import VelocityMuxNode
from amiro.sim.config import BaseSection, ObstacleSpec, SimConfig
from amiro.sim.simulator import build_sim

ARENAS = Path(__file__).resolve().parents[1] / "data" / "maps" / "arenas"
DTW_SPACING_M = 0.1  # both curves are resampled every 10 cm before DTW
PEPPER_MAX_SPEED = 0.55  # m/s, the base's hardware limit (the simulator's base allows it)

Polygon = list[tuple[float, float]]


def _box(cx: float, cy: float, sx: float, sy: float) -> Polygon:
    return [
        (cx - sx / 2, cy - sy / 2),
        (cx + sx / 2, cy - sy / 2),
        (cx + sx / 2, cy + sy / 2),
        (cx - sx / 2, cy + sy / 2),
    ]


@dataclass(frozen=True)
class Experiment:
    name: str
    arena: str  # folder under data/maps/arenas
    obstacles: tuple[Polygon, ...] = ()
    mapped: bool = True  # obstacles in the robot's map, or seen only by the lidar
    paper: dict[str, float] = field(default_factory=dict)  # Table 14 / hallway figures


EXPERIMENTS = (
    Experiment(
        "forward",
        "lab_area",
        paper={"plan_m": 2.6904, "travelled_m": 2.7145, "time_s": 8.12, "dtw": 1.7803},
    ),
    Experiment(
        "one_obstacle",
        "lab_area",
        (_box(2.35, 1.25, 0.4, 0.4),),
        paper={"plan_m": 3.3636, "travelled_m": 3.4418, "time_s": 13.035, "dtw": 9.3428},
    ),
    Experiment(
        "two_obstacles",
        "lab_area",
        (_box(1.9, 1.05, 0.4, 0.4), _box(2.9, 1.45, 0.4, 0.4)),
        paper={"plan_m": 3.3908, "travelled_m": 4.2177, "time_s": 16.034, "dtw": 18.5864},
    ),
    Experiment("hallway", "hallway", paper={"travelled_m": 17.05, "time_s": 54.41}),
    Experiment(
        "hallway_obstacles",
        "hallway",
        (_box(3.5, 0.6, 0.5, 1.1), _box(6.0, 1.4, 0.5, 1.1), _box(8.5, 0.6, 0.5, 1.1)),
        mapped=False,
        paper={"travelled_m": 18.24, "time_s": 58.11},
    ),
)


@dataclass(frozen=True)
class RunResult:
    arrived: bool
    plan_m: float
    travelled_m: float
    time_s: float
    dtw: float
    dtw_truth: float
    collisions: int
    replans: int
    plan: tuple[Pose2D, ...] = field(default=(), repr=False)  # the plan the robot followed
    driven: tuple[Pose2D, ...] = field(default=(), repr=False)  # its true path


def arena_home(arena: str) -> Path:
    return ARENAS / arena / "home.yaml"


def followed_plan(
    plans: list[tuple[float, list[Pose2D]]], track: list[tuple[float, Pose2D]]
) -> list[Pose2D]:
    """The plan the robot followed: each plan up to where the robot was when the next one
    replaced it, then the last plan in full."""
    out: list[Pose2D] = []
    for (_, path), (t_next, _) in itertools.pairwise(plans):
        here = _pose_at(track, t_next)
        pts = resample(path, DTW_SPACING_M)
        cut = int(np.argmin(np.hypot(pts[:, 0] - here.x, pts[:, 1] - here.y)))
        out.extend(Pose2D(float(x), float(y)) for x, y in pts[: cut + 1])
    out.extend(plans[-1][1])
    return out


def _pose_at(track: list[tuple[float, Pose2D]], t: float) -> Pose2D:
    """The last tracked pose at or before ``t`` (the first one if none is)."""
    before = [p for s, p in track if s <= t]
    return before[-1] if before else track[0][1]


def _dtw(plan: list[Pose2D], poses: list[Pose2D]) -> float:
    return dtw(resample(plan, DTW_SPACING_M), resample(poses, DTW_SPACING_M))


def run_once(exp: Experiment, seed: int, max_speed: float, timeout_s: float = 240.0) -> RunResult:
    """One run of ``exp`` in a fresh simulated world seeded with ``seed``."""
    home = arena_home(exp.arena)
    obstacles = [ObstacleSpec(name=f"box{i}", polygon=list(p)) for i, p in enumerate(exp.obstacles)]
    sim_cfg = SimConfig(
        home=home,
        start="start",
        obstacles=obstacles,
        base=BaseSection(max_linear=max(PEPPER_MAX_SPEED, max_speed)),
    )
    rt = Runtime(SimClock(), seed=seed)
    sim = build_sim(rt, sim_cfg)
    world = sim.world
    grid = world.live if exp.mapped else world.render()
    start = world.place("start")
    places = {name: world.place(name) for name in world.home.places}
    cfg = NavigationConfig(max_speed=max_speed)
    rt.add(build_navigation(grid, places, cfg, initial_pose=start))
    rt.add(VelocityMuxNode())  # MoveTo's commands on to /cmd_vel
    slam = rt.add(
        SlamNode(
            start, SlamParams(resolution=0.025, levels=4, size_m=2.0 * max(world.home.size) + 4.0)
        )
    )
    plans: list[tuple[float, list[Pose2D]]] = []
    truth: list[Pose2D] = []
    rt.bus.subscribe(names.PATH, PathMsg, lambda m: plans.append((rt.clock.now(), list(m.poses))))
    rt.bus.subscribe(names.GROUND_TRUTH, Pose2D, truth.append, depth=1)
    rt.start()
    rt.spin_for(0.5)  # first scans: SLAM and AMCL settle before the goal is given
    t0 = rt.clock.now()
    handle: GoalHandle[MoveToGoal, MoveToFeedback, MoveToResult] = rt.bus.send_goal(
        names.MOVE_TO, MoveToGoal(place="goal")
    )
    rt.spin_until(lambda: handle.done, timeout_s)
    elapsed = rt.clock.now() - t0
    result = handle.result if handle.done else None
    rt.stop()
    track = [(t, p) for t, p in slam.trajectory if t >= t0]
    moving = [p for _, p in track]
    plan = followed_plan(plans, track) if plans and track else []
    return RunResult(
        arrived=bool(result is not None and result.success),
        plan_m=path_length(plan),
        travelled_m=path_length(truth),
        time_s=elapsed,
        dtw=_dtw(plan, moving) if plan and moving else float("inf"),
        dtw_truth=_dtw(plan, truth) if plan and truth else float("inf"),
        collisions=sim.robot.collisions,
        replans=max(0, len(plans) - 1),
        plan=tuple(plan),
        driven=tuple(truth),
    )


def _summary(exp: Experiment, runs: list[RunResult]) -> dict[str, Any]:
    def mean(values: list[float]) -> float:
        return round(float(np.mean(values)), 4)

    row: dict[str, Any] = {
        "name": exp.name,
        "runs": len(runs),
        "arrived": sum(r.arrived for r in runs),
        "plan_m": mean([r.plan_m for r in runs]),
        "travelled_m": mean([r.travelled_m for r in runs]),
        "time_s": mean([r.time_s for r in runs]),
        "dtw": mean([r.dtw for r in runs]),
        "dtw_truth": mean([r.dtw_truth for r in runs]),
        "collisions": sum(r.collisions for r in runs),
        "replans": mean([float(r.replans) for r in runs]),
        "paper": exp.paper,
    }
    checks = [row["collisions"] == 0, row["arrived"] == len(runs)]
    checks.append(row["time_s"] <= exp.paper["time_s"])
    if "dtw" in exp.paper:
        checks.append(row["dtw"] <= exp.paper["dtw"] / 2.0)
    row["targets_met"] = all(checks)
    return row


def run_experiments(
    runs: int = 5,
    seed: int = 0,
    max_speed: float = 0.45,
    plots: Path | None = None,
    progress: bool = False,
) -> dict[str, Any]:
    """All experiments, ``runs`` seeds each; means per experiment beside the paper's.  With
    ``plots``, one PNG per experiment there (the paths over the map, as the paper's Figures
    11-14); ``progress``: a bar on stderr."""
    from tqdm import tqdm

    rows, written = [], []
    bar = tqdm(total=runs * len(EXPERIMENTS), unit="run", disable=not progress, leave=False)
    for k, exp in enumerate(EXPERIMENTS):
        results = []
        for i in range(runs):
            bar.set_description(exp.name)
            results.append(run_once(exp, seed + 1000 * k + i, max_speed))
            bar.update()
        rows.append(_summary(exp, results))
        if plots is not None:
            written.append(str(plot_runs(exp, results, plots / f"nav_{exp.name}.png")))
    bar.close()
    out: dict[str, Any] = {
        "experiments": rows,
        "localization": "amcl",
        "trajectory": "slam",
        "dtw_spacing_m": DTW_SPACING_M,
        "max_speed": max_speed,
    }
    if plots is not None:
        out["plots"] = written
    return out


def plot_runs(exp: Experiment, runs: list[RunResult], path: Path) -> Path:
    """The arena's map, the obstacles, and each run's followed plan and true path."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    world = World.load(arena_home(exp.arena))
    grid = world.render()
    data = np.asarray(grid.data).reshape(grid.height, grid.width)
    ox, oy, _ = grid.origin
    extent = (ox, ox + grid.width * grid.resolution, oy, oy + grid.height * grid.resolution)
    fig, ax = plt.subplots(figsize=(8, 8 * (extent[3] - extent[2]) / (extent[1] - extent[0]) + 1))
    ax.imshow(data == OCCUPIED, cmap="Greys", origin="lower", extent=extent, alpha=0.6)
    for box in exp.obstacles:
        xs, ys = zip(*[*box, box[0]], strict=True)
        ax.fill(xs, ys, color="tab:red", alpha=0.35, label=None)
    for i, run in enumerate(runs):
        if run.plan:
            ax.plot(*_xy(run.plan), "--", color="tab:blue", lw=1, label="plan" if i == 0 else None)
        if run.driven:
            ax.plot(*_xy(run.driven), color="tab:green", lw=1, label="driven" if i == 0 else None)
    boxes = "" if not exp.obstacles else ", boxes in red" + ("" if exp.mapped else " (not mapped)")
    ax.set_title(f"{exp.name}: {len(runs)} run{'s' * (len(runs) > 1)}{boxes}")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_aspect("equal")
    ax.legend(loc="upper right")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _xy(poses: tuple[Pose2D, ...]) -> tuple[list[float], list[float]]:
    return [p.x for p in poses], [p.y for p in poses]


def format_table(result: dict[str, Any]) -> str:
    """Ours beside the paper's (Table 14 and the hallway figures); '-' where it gives none."""

    def cell(value: float | None) -> str:
        return "-" if value is None else f"{value:.2f}"

    lines = [
        f"{'experiment':<18} {'plan m':>15} {'travelled m':>15} {'time s':>15} "
        f"{'DTW':>15} {'coll.':>5} {'arrived':>7}",
        f"{'':<18} {'ours / paper':>15} {'ours / paper':>15} {'ours / paper':>15} "
        f"{'ours / paper':>15}",
    ]
    for row in result["experiments"]:
        paper = row["paper"]
        cols = [
            f"{cell(row[k])} / {cell(paper.get(k))}".rjust(15)
            for k in ("plan_m", "travelled_m", "time_s", "dtw")
        ]
        lines.append(
            f"{row['name']:<18} {' '.join(cols)} {row['collisions']:>5} "
            f"{row['arrived']:>3}/{row['runs']:<3}"
        )
    lines.append(
        f"trajectory: {result['trajectory']}, localisation: {result['localization']}, "
        f"DTW on curves resampled every {result['dtw_spacing_m']} m, "
        f"max speed {result['max_speed']} m/s"
    )
    return "\n".join(lines)
