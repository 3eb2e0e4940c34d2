"""``amiro nav ...`` and ``amiro slam ...`` commands."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING, Any

from amiro.commands.support import (
    add_command,
    add_group,
    add_out_flag,
    emit_json,
    out_dir,
    show_progress,
)

if TYPE_CHECKING:
    from amiro.commands.support import Subcommands


def register(sub: Subcommands) -> None:
    nav_sub = add_group(
        sub, "nav", "navigation evaluations and speed benchmarks", dest="nav_command"
    )
    bm = add_command(
        nav_sub, "benchmark", _benchmark, help="random feasible start/goal pairs on a map"
    )
    bm.add_argument("--map", required=True, help="ROS map_server YAML (PGM or PNG image)")
    bm.add_argument("--trials", type=int, default=20)
    bm.add_argument("--seed", type=int, default=0)
    exp = add_command(
        nav_sub, "experiments", _experiments, help="the paper's section-4.3 experiments"
    )
    exp.add_argument("--runs", type=int, default=5, help="runs per experiment (seeds)")
    exp.add_argument("--seed", type=int, default=0)
    exp.add_argument(
        "--max-speed", type=float, default=0.45, help="m/s, up to Pepper's 0.55 (default 0.45)"
    )
    add_out_flag(exp)
    bench = add_command(nav_sub, "bench", _bench, help="per-cycle speed: A*, DWA, SLAM, AMCL")
    bench.add_argument("--seed", type=int, default=0)

    slam_sub = add_group(sub, "slam", "2D lidar SLAM", dest="slam_command")
    run = add_command(
        slam_sub, "run", _slam_run, help="SLAM over a CARMEN log, scored against its reference"
    )
    run.add_argument("--carmen", required=True, help="CARMEN log (FLASER and ODOM lines)")
    run.add_argument("--out", default="slam_out", help="directory for map and trajectory")
    run.add_argument(
        "--fov-deg",
        type=float,
        default=None,
        help="FLASER field of view (default: CARMEN's geometry for the beam count)",
    )
    run.add_argument("--max-range", type=float, default=12.0, help="ignore returns beyond (m)")
    run.add_argument(
        "--no-loop-closure", action="store_true", help="front end only (submap scan matching)"
    )
    ev = add_command(
        slam_sub,
        "evaluate",
        _slam_evaluate,
        help="SLAM over every CARMEN log in DIR: ATE, relation error, speed, plots",
    )
    ev.add_argument("dir", help="folder of CARMEN logs (.log or .log.gz) with reference poses")
    ev.add_argument("--out", default=None, help="folder for a plot and a map image per run")
    ev.add_argument(
        "--drift",
        choices=("none", "pepper", "both"),
        default="both",
        help="odometry: the log's real one (none), Pepper-like drift added (pepper), or both",
    )
    ev.add_argument("--seed", type=int, default=0, help="seed of the Pepper drift")
    log = add_command(
        slam_sub,
        "simulate",
        _slam_simulate,
        help="write a simulated CARMEN log: laps of a generated office's ring corridor",
    )
    log.add_argument("--out", required=True, help="CARMEN log to write")
    log.add_argument("--width", type=float, default=50.0, help="floor width (m)")
    log.add_argument("--height", type=float, default=60.0, help="floor height (m)")
    log.add_argument("--loops", type=int, default=3, help="laps of the ring corridor")
    log.add_argument("--seed", type=int, default=0)


def _print(result: dict[str, Any], as_json: bool) -> None:
    if as_json:
        emit_json(result)
    else:
        for key, value in result.items():
            print(f"{key}: {value}")


def _benchmark(args: argparse.Namespace) -> int:
    import numpy as np

    from amiro.core.config import ConfigError
    from amiro.core.gridmap import load_map
    from amiro.evaluation.navigation_benchmark import run_benchmark

    if args.trials < 1:
        raise ConfigError("--trials must be at least 1")
    grid = load_map(Path(args.map))
    _print(run_benchmark(grid, args.trials, np.random.default_rng(args.seed)), args.json)
    return 0


def _experiments(args: argparse.Namespace) -> int:
    from amiro.core.config import ConfigError
    from amiro.evaluation.navigation_experiments import (
        PEPPER_MAX_SPEED,
        format_table,
        run_experiments,
    )

    if args.runs < 1:
        raise ConfigError("--runs must be at least 1")
    if not 0.05 <= args.max_speed <= PEPPER_MAX_SPEED:
        raise ConfigError(f"--max-speed must be between 0.05 and {PEPPER_MAX_SPEED} m/s")
    result = run_experiments(
        args.runs, args.seed, args.max_speed, out_dir(args), show_progress(args)
    )
    if args.json:
        emit_json(result)
    else:
        print(format_table(result))
    return 0


def _bench(args: argparse.Namespace) -> int:
    import numpy as np

    from amiro.evaluation.navigation_bench import run_bench

    _print(run_bench(np.random.default_rng(args.seed)), args.json)
    return 0


def _slam_run(args: argparse.Namespace) -> int:
    from amiro.core.config import ConfigError
    from amiro.navigation.slam_run import run_slam

    if args.fov_deg is not None and not 0.0 < args.fov_deg <= 360.0:
        raise ConfigError("--fov-deg must be within (0, 360]")
    if args.max_range <= 0.0:
        raise ConfigError("--max-range must be positive")
    result = run_slam(
        Path(args.carmen),
        Path(args.out),
        args.fov_deg,
        args.max_range,
        loop_closure=not args.no_loop_closure,
    )
    _print(result, args.json)
    return 0


def _slam_evaluate(args: argparse.Namespace) -> int:
    from amiro.core.config import ConfigError
    from amiro.evaluation.slam_evaluate import evaluate_dir, format_table

    folder = Path(args.dir)
    if not folder.is_dir():
        raise ConfigError(f"{folder}: no such folder")
    drifts = {"none": ("real",), "pepper": ("pepper",), "both": ("real", "pepper")}[args.drift]
    try:
        result = evaluate_dir(folder, Path(args.out) if args.out else None, drifts, args.seed)
    except ValueError as exc:
        raise ConfigError(str(exc)) from None
    if not result["logs"]:
        raise ConfigError(f"{folder}: no CARMEN logs (*.log, *.log.gz)")
    if args.json:
        emit_json(result)
    else:
        print(format_table(result))
    return 0


def _slam_simulate(args: argparse.Namespace) -> int:
    import numpy as np

    from amiro.core.config import ConfigError
    from amiro.sim.office_log import ring_route, route_length, write_office_log

    if args.loops < 1:
        raise ConfigError("--loops must be at least 1")
    if min(args.width, args.height) < 20.0:
        raise ConfigError("--width and --height must be at least 20 m (rooms, corridor, core)")
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    scans = write_office_log(
        out, np.random.default_rng(args.seed), args.width, args.height, args.loops
    )
    length = route_length(ring_route(args.width, args.height, args.loops))
    _print({"log": str(out), "scans": scans, "route_m": round(length, 1)}, args.json)
    return 0
