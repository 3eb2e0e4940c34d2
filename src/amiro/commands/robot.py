"""``amiro robot profiles`` and ``amiro robot run``: see and try the real-robot adapters."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from amiro.commands.support import add_command, add_group, emit_report
from amiro.core import names

if TYPE_CHECKING:
    from amiro.commands.support import Subcommands


def register(sub: Subcommands) -> None:
    tools = add_group(
        sub,
        "robot",
        "real robots: profiles and adapters (ROS 2, NAOqi)",
        dest="robot_tool",
        metavar="TOOL",
    )
    add_command(tools, "profiles", _profiles, help="the shipped robot profiles")

    run = add_command(
        tools,
        "run",
        _run,
        help="drive a real robot's adapter alone for a while and report what it saw",
        description="Connects to the robot (ROS 2 driver or NAOqi), optionally says a "
        "sentence, and counts the scans, odometry and commands that went through.",
    )
    run.add_argument("--adapter", choices=("ros2", "naoqi"), required=True)
    run.add_argument("--profile", default="pepper", help="profile name or YAML (default pepper)")
    run.add_argument("--url", default=None, help="NAOqi address, e.g. tcp://192.168.1.10:9559")
    run.add_argument("--domain-id", type=int, default=None, help="ROS_DOMAIN_ID")
    run.add_argument("--duration", type=float, default=5.0, help="seconds to run (default 5)")
    run.add_argument("--say", default=None, help="a sentence for the robot to say at start")
    run.add_argument("--lang", default="en", help="language of --say (default en)")


def _profiles(args: argparse.Namespace) -> int:
    from amiro.robot.profile import load_profile, shipped_profiles

    rows = []
    for name in shipped_profiles():
        p = load_profile(name)
        rows.append(
            {
                "name": p.name,
                "base": p.base,
                "description": p.description,
                "limits": p.limits.model_dump(),
                "topics": p.topics.model_dump(),
                "naoqi": p.naoqi is not None,
            }
        )
    text = "\n".join(f"{r['name']:14} {r['base']:16} {r['description']}" for r in rows)
    return emit_report(args, {"profiles": rows}, text)


def _run(args: argparse.Namespace) -> int:
    from amiro.core.clock import WallClock
    from amiro.core.config import ConfigError, parse
    from amiro.core.messages import SpeechRequest
    from amiro.core.runtime import Runtime
    from amiro.robot.build import build_robot
    from amiro.robot.config import RobotConfig

    if args.duration <= 0:
        raise ConfigError(f"--duration must be positive, got {args.duration:g}")
    if args.adapter == "naoqi" and args.url is None:
        raise ConfigError("--adapter naoqi needs --url tcp://HOST:9559")
    data: dict[str, Any] = {"adapter": args.adapter, "profile": args.profile}
    if args.domain_id is not None:
        data["ros"] = {"domain_id": args.domain_id}
    if args.url is not None:
        data["naoqi"] = {"url": args.url}
    cfg = parse(RobotConfig, data, "amiro robot run")
    runtime = Runtime(WallClock())
    robot = build_robot(runtime, cfg)
    try:
        runtime.start()
        if args.say:
            runtime.bus.publisher(names.SAY, SpeechRequest).publish(
                SpeechRequest(args.say, lang=args.lang)
            )
        runtime.spin_for(args.duration)
    except KeyboardInterrupt:
        pass
    finally:
        runtime.stop()
        robot.close()
    report = {
        "adapter": cfg.adapter,
        "profile": robot.profile.name,
        "duration_s": args.duration,
        **robot.stats(),
    }
    return emit_report(args, report, ", ".join(f"{k}: {v}" for k, v in report.items()))
