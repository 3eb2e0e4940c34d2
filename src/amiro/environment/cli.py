"""``amiro env ...``: import health data and measure the smart environment's speed."""

from __future__ import annotations

import argparse
from typing import Any

from amiro.cli_support import add_json_flag, emit_json


def register(sub: Any) -> None:
    env = sub.add_parser("env", help="smart environment and health data")
    kinds = env.add_subparsers(dest="env_command", metavar="WHAT")
    imp = kinds.add_parser("import", help="import health measurements from CSV or JSON")
    imp.add_argument("file", help="a .csv or .json file (see docs/environment.md)")
    imp.add_argument("--db", required=True, help="SQLAlchemy URL, e.g. sqlite:///amiro.db")
    add_json_flag(imp)
    imp.set_defaults(handler=_import)
    bench = kinds.add_parser(
        "bench", help="MQTT msgs/s through the bridge, web API req/s, health queries/s"
    )
    bench.add_argument("--mqtt", help="broker as mqtt://HOST:PORT (else MQTT is skipped)")
    bench.add_argument("--users", type=int, default=20, help="users with a year of data")
    add_json_flag(bench)
    bench.set_defaults(handler=_bench)

    def _no_kind(args: argparse.Namespace) -> int:
        env.print_help()
        return 2

    env.set_defaults(handler=_no_kind)


def _import(args: argparse.Namespace) -> int:
    from amiro.environment.health_import import import_file
    from amiro.environment.health_store import HealthStore

    store = HealthStore(args.db)
    count = import_file(store, args.file)
    store.close()
    if args.json:
        emit_json({"imported": count, "file": args.file})
    else:
        print(f"imported {count} measurements from {args.file}")
    return 0


def _bench(args: argparse.Namespace) -> int:
    from amiro.core.config import ConfigError
    from amiro.environment.bench import bench_env
    from amiro.environment.mqtt_bridge import parse_url

    if args.users < 1:
        raise ConfigError(f"--users must be at least 1, got {args.users}")
    if args.mqtt:
        parse_url(args.mqtt)
    result = bench_env(args.mqtt, args.users)
    if args.json:
        emit_json(result)
    else:
        for key, value in result.items():
            print(f"{key:24s} {value}")
    return 0
