"""``amiro record hydration --out FILE.mcap`` and ``amiro replay FILE.mcap``."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from amiro.cli_support import add_json_flag, emit_json


def register(sub: Any) -> None:
    record = sub.add_parser("record", help="record a run to MCAP (ROS 2 schemas; Foxglove)")
    runs = record.add_subparsers(dest="recorded", metavar="RUN")
    hyd = runs.add_parser("hydration", help="the embedded hydration scenario")
    hyd.add_argument("--out", type=Path, required=True, help="MCAP file to write")
    hyd.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    hyd.add_argument("--topics", default="", help="comma-separated topics (default: all)")
    add_json_flag(hyd)
    hyd.set_defaults(handler=_record_hydration)

    def _no_run(args: argparse.Namespace) -> int:
        record.print_help()
        return 2

    record.set_defaults(handler=_no_run)

    replay = sub.add_parser("replay", help="replay an MCAP recording into the bus")
    replay.add_argument("file", type=Path, help="MCAP file")
    replay.add_argument("--speed", type=float, default=None, help="pace (default: max speed)")
    replay.add_argument("--ros2", action="store_true", help="also publish on ROS 2")
    replay.add_argument("--domain-id", type=int, default=None, help="ROS_DOMAIN_ID")
    add_json_flag(replay)
    replay.set_defaults(handler=_replay)


def _topics(text: str) -> list[str] | None:
    return [t for t in text.split(",") if t] or None


def _record_hydration(args: argparse.Namespace) -> int:
    from amiro.recording.runs import record_hydration

    report = record_hydration(args.out, args.seed, _topics(args.topics))
    if args.json:
        emit_json(report)
    else:
        print(f"recorded {report['messages']} messages to {report['file']}")
    return 0


def _replay(args: argparse.Namespace) -> int:
    from amiro.recording.runs import replay

    report = replay(args.file, args.speed, args.ros2, args.domain_id)
    if args.json:
        emit_json(report)
    else:
        print(f"replayed {report['messages']} messages over {report['duration_s']} s")
    return 0
