"""``amiro env ...``: import health data and measure the smart environment's speed."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from amiro.commands.support import add_command, add_group, emit_report

if TYPE_CHECKING:
    from amiro.commands.support import Subcommands


def register(sub: Subcommands) -> None:
    kinds = add_group(sub, "env", "smart environment and health data", "env_command", "WHAT")
    imp = add_command(kinds, "import", _import, help="import health measurements from CSV or JSON")
    imp.add_argument("file", help="a .csv or .json file (see docs/environment.md)")
    imp.add_argument("--db", required=True, help="SQLAlchemy URL, e.g. sqlite:///amiro.db")
    bench = add_command(
        kinds,
        "bench",
        _bench,
        help="MQTT msgs/s through the bridge, web API req/s, health queries/s",
    )
    bench.add_argument("--mqtt", help="broker as mqtt://HOST:PORT (else MQTT is skipped)")
    bench.add_argument("--users", type=int, default=20, help="users with a year of data")


def _import(args: argparse.Namespace) -> int:
    from amiro.environment.health_import import import_file
    from amiro.environment.health_store import HealthStore

    store = HealthStore(args.db)
    count = import_file(store, args.file)
    store.close()
    report = {"imported": count, "file": args.file}
    return emit_report(args, report, f"imported {count} measurements from {args.file}")


def _bench(args: argparse.Namespace) -> int:
    from amiro.core.config import ConfigError
    from amiro.environment.mqtt_bridge import parse_url
    from amiro.evaluation.environment_bench import bench_env

    if args.users < 1:
        raise ConfigError(f"--users must be at least 1, got {args.users}")
    if args.mqtt:
        parse_url(args.mqtt)
    result = bench_env(args.mqtt, args.users)
    return emit_report(args, result, "\n".join(f"{k:24s} {v}" for k, v in result.items()))
