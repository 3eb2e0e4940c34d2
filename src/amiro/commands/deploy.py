"""``amiro sim --ros2``, ``amiro node NAME``, ``amiro launch FILE`` and ``amiro ros2 bench``."""

from __future__ import annotations

import argparse
import json
import tempfile
from pathlib import Path
from typing import TYPE_CHECKING, Any

from amiro.commands.support import add_command, add_group, emit_report

if TYPE_CHECKING:
    from amiro.commands.support import Subcommands


def register(sub: Subcommands) -> None:
    sim = add_command(
        sub,
        "sim",
        _sim,
        help="the simulated home as a ROS 2 node: /scan, /odom, /map, /clock; drive it on /cmd_vel",
    )
    sim.add_argument("--ros2", action="store_true", help="publish and subscribe over ROS 2")
    sim.add_argument(
        "--navigation",
        action="store_true",
        help="also run amiro's navigation, serving Nav2's /navigate_to_pose "
        "(nav2_msgs/action/NavigateToPose) and amiro's own MoveTo action",
    )
    sim.add_argument("--speed", type=float, default=1.0, help="sim seconds per real second")
    sim.add_argument("--duration", type=float, default=None, help="stop after this sim time (s)")
    sim.add_argument(
        "--camera-rate",
        type=float,
        default=2.0,
        help="rendered RGB-D frames per second on /camera/* (default 2; 0: no images)",
    )
    sim.add_argument(
        "--camera-size", default="320x240", help="rendered image size WxH (default 320x240)"
    )
    _common(sim)

    node = add_command(
        sub, "node", _node, help="run one process of a split deployment (sim, edge, cloud)"
    )
    node.add_argument("name", help="process name; also the role when --config is not given")
    node.add_argument("--config", type=Path, help="the process's YAML configuration")
    _common(node)

    launch = add_command(
        sub, "launch", _launch, help="start, watch and stop a deployment's processes"
    )
    launch.add_argument("deployment", type=Path, help="deployment YAML")
    launch.add_argument("--only", default="", help="comma-separated processes to run here")
    launch.add_argument("--domain-id", type=int, default=None, help="override ROS_DOMAIN_ID")
    launch.add_argument("--log-dir", type=Path, default=None, help="process logs and reports")

    tools = add_group(sub, "ros2", "ROS 2 bridge tools", dest="ros2_tool", metavar="TOOL")
    bench = add_command(
        tools, "bench", _bench, help="bridge latency and throughput vs the in-process bus"
    )
    bench.add_argument("--seconds", type=float, default=3.0, help="duration of each measurement")
    bench.add_argument("--domain-id", type=int, default=None)


def _common(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--domain-id", type=int, default=None, help="ROS_DOMAIN_ID")
    parser.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    parser.add_argument("--report", type=Path, default=None, help="write the JSON report here")
    parser.add_argument("--events", type=Path, default=None, help="append events as JSON lines")


def _finish(args: argparse.Namespace, report: dict[str, Any]) -> int:
    if args.report is not None:
        args.report.write_text(json.dumps(report, default=str), encoding="utf-8")
    text = f"{report['process']}: {report['outcome']} at {report['sim_time_s']} s sim time"
    return emit_report(args, report, text)


def _with_domain(data: dict[str, Any], domain_id: int | None) -> dict[str, Any]:
    if domain_id is not None:
        data.setdefault("ros", {})["domain_id"] = domain_id
    return data


def _sim(args: argparse.Namespace) -> int:
    from amiro.core import names
    from amiro.core.config import ConfigError, parse
    from amiro.deploy.config import NodeConfig
    from amiro.deploy.process import run_process

    if not args.ros2:
        raise ConfigError("amiro sim only runs as a ROS 2 node for now: add --ros2")
    data: dict[str, Any] = {"role": "sim", "speed": args.speed, "duration_s": args.duration}
    if args.navigation:
        data["serve_actions"] = [names.MOVE_TO, names.NAVIGATE_TO_POSE]
    if args.camera_rate != 0:
        data["camera"] = {"rate_hz": args.camera_rate, **_image_size(args.camera_size)}
    node = parse(NodeConfig, _with_domain(data, args.domain_id), "amiro sim")
    return _finish(args, run_process("sim", node, args.seed, args.events))


def _image_size(text: str) -> dict[str, int]:
    from amiro.core.config import ConfigError

    width, sep, height = text.partition("x")
    if not (sep and width.isdigit() and height.isdigit()):
        raise ConfigError(f"--camera-size {text!r}: expected WIDTHxHEIGHT, e.g. 320x240")
    return {"width": int(width), "height": int(height)}


def _node(args: argparse.Namespace) -> int:
    from amiro.core.config import ConfigError, parse, read_yaml
    from amiro.deploy.config import NodeConfig
    from amiro.deploy.process import run_process

    if args.config is not None:
        data = read_yaml(args.config) or {}
        source = str(args.config)
    else:
        data, source = {"role": args.name}, f"amiro node {args.name}"
    if not isinstance(data, dict):
        raise ConfigError(f"{source}: expected a mapping at the top level")
    if args.config is not None and isinstance(data.get("system"), str):
        data["system"] = str(args.config.parent / data["system"])  # beside the node's file
    node = parse(NodeConfig, _with_domain(data, args.domain_id), source)
    return _finish(args, run_process(args.name, node, args.seed, args.events))


def _launch(args: argparse.Namespace) -> int:
    from amiro.core.clock import wall_seconds
    from amiro.deploy.launch import Launcher, load_deployment

    dep = load_deployment(args.deployment)
    log_dir = args.log_dir or Path(tempfile.mkdtemp(prefix=f"amiro-{dep.name}-"))
    only = tuple(n for n in args.only.split(",") if n)
    launcher = Launcher(dep, log_dir, only, args.domain_id)
    started = wall_seconds()
    try:
        outcome = launcher.run_all()
    except KeyboardInterrupt:
        outcome = "interrupted"
    unclean = sorted(launcher.unclean_exits())
    reports = {}
    for name in launcher.children:
        path = launcher.report_path(name)
        if path.is_file():
            reports[name] = json.loads(path.read_text(encoding="utf-8"))
    report = {
        "deployment": dep.name,
        "outcome": outcome,
        "wall_time_s": round(wall_seconds() - started, 3),
        "log_dir": str(log_dir),
        "processes": launcher.summary(),
        "unclean_exits": unclean,
        "launch_events": launcher.events,
        "acks": [
            a
            for spec in dep.processes
            if spec.ends_deployment
            for a in reports.get(spec.name, {}).get("acks", [])
        ],
        "reports": {n: {k: v for k, v in r.items() if k != "events"} for n, r in reports.items()},
    }
    text = f"{dep.name}: {outcome} in {report['wall_time_s']} s; logs in {log_dir}"
    if report["unclean_exits"]:
        text += f"\nnot ended cleanly (see their .log): {', '.join(unclean)}"
    return emit_report(args, report, text)


def _bench(args: argparse.Namespace) -> int:
    from amiro.ros2.bench import bench_bridge

    result = bench_bridge(args.seconds, args.domain_id)
    return emit_report(args, result, json.dumps(result, indent=2))
