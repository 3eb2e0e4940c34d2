"""The ``amiro`` command line.

Every command has ``--help``; with ``--json`` it prints exactly one JSON object on stdout
(logs go to stderr).  Bad input exits with code 2 and one line on stderr, no traceback.
Building the parser imports only the packages' ``cli.py`` files, which keep their heavy
imports inside the handlers, so ``amiro --help`` answers at once.
"""

from __future__ import annotations

import argparse
import logging
import os
import sys
from collections.abc import Sequence
from typing import Any, NoReturn

from amiro import __version__
from amiro.commands.support import Handler


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> Any:  # argparse prints usage + exits 2; keep it one line
        self.exit(2, f"{self.prog}: error: {message}\n")


def build_parser() -> argparse.ArgumentParser:
    import amiro.commands.activity as activity_cli
    import amiro.commands.bench as bench_cli
    import amiro.commands.deploy as ros2_cli
    import amiro.commands.dialogue as dialogue_cli
    import amiro.commands.environment as environment_cli
    import amiro.commands.navigation as navigation_cli
    import amiro.commands.perception as perception_cli
    import amiro.commands.planning as planning_cli
    import amiro.commands.recording as recording_cli
    import amiro.commands.robot as robot_cli
    import amiro.commands.scenarios as scenarios_cli
    import amiro.commands.serve as serve_cli

    parser = _Parser(
        prog="amiro",
        description="amiro: an open framework for assistive social robots.",
    )
    parser.add_argument("--version", action="version", version=f"amiro {__version__}")
    parser.add_argument("-v", "--verbose", action="store_true", help="debug logging on stderr")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    scenarios_cli.register(sub)
    serve_cli.register(sub)
    navigation_cli.register(sub)
    perception_cli.register(sub)
    activity_cli.register(sub)
    dialogue_cli.register(sub)
    environment_cli.register(sub)
    planning_cli.register(sub)
    ros2_cli.register(sub)
    robot_cli.register(sub)
    recording_cli.register(sub)
    bench_cli.register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    logging.basicConfig(
        level=logging.DEBUG if args.verbose else logging.WARNING,
        format="%(levelname)s %(name)s: %(message)s",
        stream=sys.stderr,
    )
    handler: Handler | None = getattr(args, "handler", None)
    if handler is None:
        parser.print_help()
        return 2
    from amiro.core.config import ConfigError  # pydantic: loaded only once a command runs

    try:
        return handler(args)
    except ConfigError as exc:
        print(f"amiro: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("amiro: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        # The reader went away (`amiro ... --json | head`): not an error of ours.  Point
        # stdout at /dev/null so the interpreter's final flush does not fail again.
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 141
    except OSError as exc:
        # A path the user gave that cannot be read or written (missing, a file where a
        # folder should be, no permission): one line, unless -v asks for the traceback.
        if exc.filename is None or args.verbose:
            raise
        print(f"amiro: error: {exc.filename}: {exc.strerror}", file=sys.stderr)
        return 2


def exit_process(code: int) -> NoReturn:
    """Exit with ``code``.  A process that used rclpy skips the interpreter's final
    teardown (its reports are written by then): garbage-collecting rclpy's C objects at
    shutdown can hang, and a deployment's process then has to be killed."""
    if "rclpy" in sys.modules:
        logging.shutdown()
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)
    sys.exit(code)


def run() -> NoReturn:
    """The ``amiro`` console command."""
    exit_process(main())


if __name__ == "__main__":
    run()
