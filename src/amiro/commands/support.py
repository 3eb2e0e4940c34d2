"""Small helpers shared by the command-line entry points.

They import nothing heavy: ``amiro --help`` builds every command's parser, so a ``cli.py``
keeps its module level to argparse and these helpers, and imports its work in the handlers.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import sys
from collections.abc import Callable
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from typing import TypeAlias

    Subcommands: TypeAlias = argparse._SubParsersAction[Any]  # of the CLI's parser class

Handler = Callable[[argparse.Namespace], int]


def add_json_flag(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--json", action="store_true", help="print exactly one JSON object on stdout"
    )


DEFAULT_OUT = Path("amiro-out")


def add_out_flag(parser: argparse.ArgumentParser) -> None:
    """``--out DIR``: where an evaluation writes its plots and files."""
    parser.add_argument(
        "--out", type=Path, default=DEFAULT_OUT, help=f"output folder (default ./{DEFAULT_OUT})"
    )


def out_dir(args: argparse.Namespace) -> Path:
    """The ``--out`` folder, made if needed (a one-line error if it cannot be)."""
    from amiro.core.config import ConfigError  # pydantic: only once a command runs

    out: Path = args.out
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ConfigError(f"--out {out}: {exc.strerror}") from None
    return out


def writable_file(path: Path, flag: str) -> Path:
    """``path`` if a file can be written there (checked before the work that fills it)."""
    from amiro.core.config import ConfigError

    try:
        with path.open("ab"):
            pass
    except OSError as exc:
        raise ConfigError(f"{flag} {path}: cannot write: {exc.strerror}") from None
    return path


def out_file(args: argparse.Namespace, name: str) -> Path:
    """``name`` inside the ``--out`` folder."""
    return out_dir(args) / name


def show_progress(args: argparse.Namespace) -> bool:
    """A progress bar on stderr: for a person at a terminal, never with ``--json``."""
    return not getattr(args, "json", False) and sys.stderr.isatty()


def add_group(
    sub: Subcommands, name: str, help: str, dest: str, metavar: str = "COMMAND"
) -> Subcommands:
    """A command made of subcommands (``amiro nlu parse``); alone it prints its help, exit 2."""
    group: argparse.ArgumentParser = sub.add_parser(name, help=help)
    group.set_defaults(handler=partial(_print_help, group))
    return group.add_subparsers(dest=dest, metavar=metavar)


def _print_help(parser: argparse.ArgumentParser, _args: argparse.Namespace) -> int:
    parser.print_help()
    return 2


def add_command(
    sub: Subcommands,
    name: str,
    handler: Handler,
    help: str,
    description: str | None = None,
    with_json: bool = True,
) -> argparse.ArgumentParser:
    """A command that runs ``handler``; with ``with_json``, it takes the ``--json`` flag."""
    parser: argparse.ArgumentParser = sub.add_parser(name, help=help, description=description)
    parser.set_defaults(handler=handler)
    if with_json:
        add_json_flag(parser)
    return parser


def emit_report(args: argparse.Namespace, report: dict[str, Any], text: str) -> int:
    """The report as one JSON object with ``--json``, else ``text`` for a person; exit 0."""
    if args.json:
        emit_json(report)
    else:
        print(text)
    return 0


def jsonable(value: Any) -> Any:
    """Plain JSON types from dataclasses, numpy scalars and non-finite floats."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {f.name: jsonable(getattr(value, f.name)) for f in dataclasses.fields(value)}
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple | set):
        return [jsonable(v) for v in value]
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, str | int | bool) or value is None:
        return value
    item = getattr(value, "item", None)  # numpy scalar
    if callable(item):
        return jsonable(item())
    return str(value)


def emit_json(obj: dict[str, Any]) -> None:
    json.dump(jsonable(obj), sys.stdout, ensure_ascii=False)
    sys.stdout.write("\n")
    sys.stdout.flush()
