"""Deliver a notification to a person in another room when a door on the way is closed.

Maria is on the living-room couch; the robot starts at its dock in the hallway and believes,
as its map shows, that every door is open.  By default the hallway–living-room door is closed:
the lidar sees it on the way, the plan no longer holds, and the robot re-plans.  John, in the
hallway, is asked to open it; with ``help=False`` he declines and the robot re-plans again,
through the kitchen.  With every way in closed, planning fails and says why.  What the robot
says (the notification, its requests) is in ``lang``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from amiro.behavior.planning.config import Engine
from amiro.behavior.planning.dispatch import OPEN_DOOR_REQUEST
from amiro.behavior.planning.executive import PlanExecutive
from amiro.behavior.planning.knowledge import KnowledgeBase
from amiro.behavior.planning.problem import Goal
from amiro.core.config import ConfigError
from amiro.dialogue.phrases import check_language, phrase
from amiro.scenarios.common import base_config_data, run_scenario
from amiro.system import System, SystemConfig

PERSON, HELPER = "maria", "john"
KNOWN_ROOMS = {PERSON: "living_room", HELPER: "hallway"}
HELPER_POSE = {"x": 2.4, "y": 4.6, "theta": 0.0}
MESSAGE = "notification_visit"  # phrase key


@dataclass(frozen=True)
class DeliveryOptions:
    seed: int = 1
    closed_doors: tuple[str, ...] = ("living_door",)
    help: bool = True
    engine: Engine = "kairos"
    live: bool = False
    speed: float | None = None
    config_path: str | None = None
    timeout_s: float = 900.0
    lang: str = "en"
    check_activity: str | None = None  # also check that Maria does this (e.g. play_phone)


def scenario_config(opts: DeliveryOptions) -> SystemConfig:
    data = base_config_data(opts.config_path, opts.seed)
    sim = data.setdefault("sim", {})
    reply = "confirm" if opts.help else "deny"
    residents = [
        {"name": PERSON, "at": "couch_left", "posture": "sitting_couch", "activity": "play_phone"},
        {"name": HELPER, "pose": HELPER_POSE, "script": {OPEN_DOOR_REQUEST: {"reply": reply}}},
    ]
    sim["residents"] = [
        *residents,
        *[r for r in sim.get("residents", []) if r["name"] not in KNOWN_ROOMS],
    ]
    sim["doors"] = {**sim.get("doors", {}), **dict.fromkeys(opts.closed_doors, False)}
    env = data.setdefault("environment", {})
    env["rules"] = []  # no hydration alert in this scenario
    behavior = data.setdefault("behavior", {})
    behavior["planner"] = {
        **behavior.get("planner", {}),
        "engine": opts.engine,
        "people": dict(KNOWN_ROOMS),
    }
    return SystemConfig.model_validate(data)


def run_delivery(opts: DeliveryOptions) -> dict[str, Any]:
    """Plan, deliver, re-plan as the home turns out to differ from the map; the report has the
    contract's keys plus the plans and what the robot learned."""
    cfg = scenario_config(opts)
    lang = check_language(opts.lang)
    parts: dict[str, Any] = {}

    def setup(system: System) -> None:
        world = system.world
        unknown = sorted(set(opts.closed_doors) - set(world.doors))
        if unknown:
            raise ConfigError(
                f"unknown door(s) {', '.join(unknown)} (doors: {', '.join(world.doors)})"
            )
        executive = system.planner
        kb = system.engine.modules.knowledge
        assert executive is not None and kb is not None  # behavior.planner is set above
        goals = [Goal("notified", PERSON)]
        if opts.check_activity is not None:
            goals.append(Goal("activity_checked", PERSON))
        executive.request(
            goals,
            {
                "person": PERSON,
                "message": phrase(MESSAGE, lang, {"name": PERSON.title()}),
                "activity": opts.check_activity,
                "lang": lang,
            },
            behavior="deliver_notification",
        )
        parts.update(kb=kb, executive=executive)

    done = run_scenario(
        cfg,
        lambda _system: bool(parts) and parts["executive"].done,
        live=opts.live,
        speed=opts.speed,
        timeout_s=opts.timeout_s,
        setup=setup,
    )
    executive: PlanExecutive = parts["executive"]
    kb: KnowledgeBase = parts["kb"]
    return {
        "scenario": "deliver_notification",
        "outcome": executive.status if executive.done else "timeout",
        "explanation": executive.explanation,
        "seed": opts.seed,
        "closed_doors": list(opts.closed_doors),
        "help": opts.help,
        "check_activity": opts.check_activity,
        "hearing": done.system.dialogue.hearing,
        **done.timing(),
        "steps": [r.to_dict() for run in executive.runs for r in run.records],
        "plans": [p.to_dict() for p in executive.plans],
        "replans": max(len(executive.plans) - 1, 0),
        "learned": [c.to_dict() for c in kb.changes],
        "collisions": done.system.require_sim("the delivery report").robot.collisions,
        "events": done.recorder.events,
    }
