"""``amiro run SCENARIO``: run a shipped scenario in the simulated home."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from amiro.commands.support import add_command, add_group, emit_json

if TYPE_CHECKING:
    from amiro.commands.support import Subcommands


def register(sub: Subcommands) -> None:
    scenarios = add_group(
        sub, "run", "run a scenario in the simulated home", dest="scenario", metavar="SCENARIO"
    )
    hyd = add_command(
        scenarios,
        "hydration",
        _run_hydration,
        help="the paper's section-5 scenario: find the person, remind them to drink, check",
        description="A hot room triggers a hydration reminder: the robot searches for the "
        "resident, goes to them, reminds them, listens, watches them drink and acknowledges "
        "to the smart home.",
    )
    hyd.add_argument("--headless", action="store_true", help="no live log, run at full speed")
    hyd.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    hyd.add_argument("--lang", default="en", help="the resident's language: en, fr or ro")
    hyd.add_argument(
        "--speed",
        type=float,
        default=None,
        help="simulated seconds per real second for the live log (default 4; headless: max)",
    )
    hyd.add_argument("--config", help="YAML configuration overriding the defaults")
    branch = hyd.add_mutually_exclusive_group()
    branch.add_argument("--person-absent", action="store_true", help="the resident is out")
    branch.add_argument(
        "--unreachable", action="store_true", help="the way to the resident is blocked"
    )
    branch.add_argument(
        "--no-confirmation", action="store_true", help="the resident does not answer at first"
    )
    branch.add_argument(
        "--activity-missed",
        action="store_true",
        help="the robot cannot see the resident drink (occluded skeleton)",
    )

    deliver = add_command(
        scenarios,
        "deliver-notification",
        _run_delivery,
        help="deliver a notification across the home, re-planning when a door is closed",
        description="The robot plans (PDDL) a way to Maria in the living room, finds a door "
        "on the way closed, re-plans, asks John for help or takes another route, and delivers.",
    )
    deliver.add_argument("--headless", action="store_true", help="no live log, run at full speed")
    deliver.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    deliver.add_argument(
        "--closed-door",
        action="append",
        metavar="DOOR",
        help="a door that is closed (repeat for several; default living_door; 'none' for none)",
    )
    deliver.add_argument("--no-help", action="store_true", help="John declines to open the door")
    deliver.add_argument(
        "--engine",
        default="kairos",
        help="planning engine: kairos (default), pyperplan or fast-downward (GPL, optional)",
    )
    deliver.add_argument("--speed", type=float, default=None, help="as for hydration")
    deliver.add_argument("--config", help="YAML configuration overriding the defaults")
    deliver.add_argument("--lang", default="en", help="what the robot says: en, ro or fr")
    deliver.add_argument(
        "--check-activity",
        metavar="ACTIVITY",
        help="after delivering, check that Maria does ACTIVITY (e.g. play_phone)",
    )


def _run_hydration(args: argparse.Namespace) -> int:
    from amiro.scenarios.hydration import HydrationOptions, run_hydration

    branch = next(
        (
            name
            for name in ("person_absent", "unreachable", "no_confirmation", "activity_missed")
            if getattr(args, name)
        ),
        None,
    )
    options = HydrationOptions(
        seed=args.seed,
        lang=args.lang,
        branch=branch,
        live=not (args.headless or args.json),
        speed=args.speed,
        config_path=args.config,
    )
    return _finish(args, run_hydration(options))


def _run_delivery(args: argparse.Namespace) -> int:
    from amiro.commands.planning import check_engine
    from amiro.scenarios.deliver_notification import DeliveryOptions, run_delivery

    doors = args.closed_door or ["living_door"]
    options = DeliveryOptions(
        seed=args.seed,
        closed_doors=tuple(d for d in doors if d != "none"),
        help=not args.no_help,
        engine=check_engine(args.engine),
        live=not (args.headless or args.json),
        speed=args.speed,
        config_path=args.config,
        lang=args.lang,
        check_activity=args.check_activity,
    )
    return _finish(args, run_delivery(options))


def _finish(args: argparse.Namespace, report: dict[str, Any]) -> int:
    """The JSON report, or a summary when headless (the live log has said it all)."""
    if args.json:
        emit_json(report)
    elif args.headless:
        print(f"{report['scenario']}: {report['outcome']} in {report['sim_time_s']} s sim time")
        if report.get("explanation"):
            print(report["explanation"])
    return 0
