"""``amiro bench ...``: speed measurements (rates on this machine, never pass/fail)."""

from __future__ import annotations

import argparse
from typing import Any

from amiro.cli_support import add_json_flag, emit_json


def register(sub: Any) -> None:
    bench = sub.add_parser("bench", help="speed measurements")
    kinds = bench.add_subparsers(dest="bench", metavar="WHAT")
    core = kinds.add_parser(
        "core", help="bus messages/s, engine dispatches/s, simulator steps/s with the lidar"
    )
    add_json_flag(core)
    core.set_defaults(handler=_core)

    def _no_kind(args: argparse.Namespace) -> int:
        bench.print_help()
        return 2

    bench.set_defaults(handler=_no_kind)


def _core(args: argparse.Namespace) -> int:
    from amiro.evaluation.bench_core import bench_core

    result = bench_core()
    if args.json:
        emit_json(result)
    else:
        for key, value in result.items():
            print(f"{key:28s} {value:>12,}")
    return 0
