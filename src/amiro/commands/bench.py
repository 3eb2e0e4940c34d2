"""``amiro bench ...``: speed measurements (rates on this machine, never pass/fail)."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from amiro.commands.support import add_command, add_group, emit_report

if TYPE_CHECKING:
    from amiro.commands.support import Subcommands


def register(sub: Subcommands) -> None:
    kinds = add_group(sub, "bench", "speed measurements", dest="bench", metavar="WHAT")
    add_command(
        kinds,
        "core",
        _core,
        help="bus messages/s, engine dispatches/s, simulator steps/s with the lidar",
    )


def _core(args: argparse.Namespace) -> int:
    from amiro.evaluation.core_bench import bench_core

    result = bench_core()
    return emit_report(args, result, "\n".join(f"{k:28s} {v:>12,}" for k, v in result.items()))
