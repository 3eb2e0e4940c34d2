"""``amiro plan``: the PDDL of the default apartment, and the planning benchmark."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, cast

from amiro.commands.support import add_command, add_group, emit_report

if TYPE_CHECKING:
    from amiro.behavior.planning.config import Engine, PlanningConfig
    from amiro.commands.support import Subcommands

ENGINES = ("kairos", "pyperplan", "fast-downward")


def register(sub: Subcommands) -> None:
    cmds = add_group(
        sub, "plan", "declarative planning (PDDL) of the robot's errands", dest="plan_command"
    )
    bench = add_command(
        cmds,
        "bench",
        _bench,
        help="planning time for generated homes of 5, 10 and 20 rooms",
        description="Plans a delivery across generated homes of 5, 10 and 20 rooms and "
        "reports the median planning time (problem generation and engine, milliseconds) of a "
        "new planner and of a re-plan after a door of the plan is found closed.",
    )
    _engine_args(bench)
    bench.add_argument("--trials", type=int, default=5, help="plans per home (default 5)")
    bench.add_argument("--seed", type=int, default=0, help="seed of the generated homes")

    pddl = add_command(
        cmds,
        "pddl",
        _pddl,
        help="print the PDDL domain and problem of the default apartment",
        description="The domain generated for the shipped apartment and a problem: deliver a "
        "notification to Maria in the living room, starting from the dock.",
    )
    pddl.add_argument("--temporal", action="store_true", help="the durative variant")


def _engine_args(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--engine", default="kairos", help=f"one of {', '.join(ENGINES)}")
    parser.add_argument("--temporal", action="store_true", help="durative actions (kairos)")


def check_engine(engine: str) -> Engine:
    """The engine's name, or a one-line ConfigError listing the choices."""
    from amiro.core.config import ConfigError

    if engine not in ENGINES:
        raise ConfigError(f"unknown engine {engine!r} (choices: {', '.join(ENGINES)})")
    return cast("Engine", engine)


def _config(args: argparse.Namespace) -> PlanningConfig:
    from amiro.behavior.planning.config import PlanningConfig
    from amiro.core.config import parse

    data = {"engine": check_engine(args.engine), "temporal": args.temporal}
    return parse(PlanningConfig, data, "--engine")


def _bench(args: argparse.Namespace) -> int:
    from amiro.behavior.planning.bench import run_bench
    from amiro.core.config import ConfigError

    if args.trials < 1:
        raise ConfigError(f"--trials must be at least 1, got {args.trials}")
    report = run_bench(_config(args), seed=args.seed, trials=args.trials)
    lines = [
        f"{home['rooms']:3d} rooms, {home['doors']:3d} doors: {home['ms_median']:8.1f} ms, "
        f"re-plan {home['replan_ms_median']:6.1f} ms "
        f"(medians of {report['trials']}, {home['plan_steps']} actions)"
        for home in report["homes"]
    ]
    lines.append(f"target < 100 ms for 10 rooms: {'met' if report['meets_target'] else 'missed'}")
    return emit_report(args, report, "\n".join(lines))


def _pddl(args: argparse.Namespace) -> int:
    from unified_planning.io import PDDLWriter

    from amiro.behavior.planning.domain import home_domain
    from amiro.behavior.planning.knowledge import KnowledgeBase
    from amiro.behavior.planning.problem import Goal, RobotState, make_problem
    from amiro.behavior.planning.topology import topology_from_world
    from amiro.home.world import World, default_home_path

    world = World.load(default_home_path())
    kb = KnowledgeBase(topology_from_world(world), {"maria": "living_room", "john": "hallway"})
    dock = world.place("dock")
    problem = make_problem(
        home_domain(args.temporal),
        kb,
        RobotState("hallway", dock.x, dock.y),
        [Goal("notified", "maria")],
    )
    writer = PDDLWriter(problem)
    domain, task = writer.get_domain(), writer.get_problem()
    return emit_report(args, {"domain": domain, "problem": task}, f"{domain}\n{task}")
