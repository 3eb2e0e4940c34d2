"""``python -m amiro.ros2 ...``: what ``amiro launch`` spawns for each process.

It is the ``amiro`` command line with the ROS 2 commands added if ``amiro.cli`` does not
register them yet, so a deployment runs the same code whichever way it is started.
"""

from __future__ import annotations

import argparse
import sys
from typing import NoReturn

from amiro import cli
from amiro.ros2.cli import register

_build_parser = cli.build_parser


def build_parser() -> argparse.ArgumentParser:
    parser = _build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    if "node" not in sub.choices:
        register(sub)
    return parser


def run() -> NoReturn:
    cli.build_parser = build_parser  # this process's entry point: nothing else uses the CLI
    cli.exit_process(cli.main(sys.argv[1:]))


if __name__ == "__main__":
    run()
