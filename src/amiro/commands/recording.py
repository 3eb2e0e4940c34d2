"""``amiro record hydration --out FILE.mcap`` and ``amiro replay FILE.mcap``."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING

from amiro.commands.support import add_command, add_group, emit_report, writable_file

if TYPE_CHECKING:
    from amiro.commands.support import Subcommands


def register(sub: Subcommands) -> None:
    runs = add_group(
        sub,
        "record",
        "record a run to MCAP (ROS 2 schemas; Foxglove)",
        dest="recorded",
        metavar="RUN",
    )
    hyd = add_command(runs, "hydration", _record_hydration, help="the embedded hydration scenario")
    hyd.add_argument("--out", type=Path, required=True, help="MCAP file to write")
    hyd.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    hyd.add_argument("--topics", default="", help="comma-separated topics (default: all)")

    replay = add_command(sub, "replay", _replay, help="replay an MCAP recording into the bus")
    replay.add_argument("file", type=Path, help="MCAP file")
    replay.add_argument("--speed", type=float, default=None, help="pace (default: max speed)")
    replay.add_argument("--ros2", action="store_true", help="also publish on ROS 2")
    replay.add_argument("--domain-id", type=int, default=None, help="ROS_DOMAIN_ID")


def _topics(text: str) -> list[str] | None:
    return [t for t in text.split(",") if t] or None


def _record_hydration(args: argparse.Namespace) -> int:
    from amiro.recording.runs import record_hydration

    out = writable_file(args.out, "--out")
    report = record_hydration(out, args.seed, _topics(args.topics))
    text = f"recorded {report['messages']} messages to {report['file']}"
    return emit_report(args, report, text)


def _replay(args: argparse.Namespace) -> int:
    from amiro.recording.runs import replay

    report = replay(args.file, args.speed, args.ros2, args.domain_id)
    text = f"replayed {report['messages']} messages over {report['duration_s']} s"
    return emit_report(args, report, text)
