"""The paper's section-5 scenario in the simulated home.

The living room heats up; the environment rule raises a hydration alert; the handler builds
the hydration behaviour (data/behaviors/hydration.yaml); the robot searches for Maria, goes
to her, reminds her, listens, watches her drink and acknowledges to the smart home.  Each
``branch`` changes the world so that one failure edge of the behaviour is taken.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from amiro.core.config import ConfigError
from amiro.dialogue.phrases import check_language
from amiro.scenarios.common import base_config_data, run_scenario
from amiro.system import System, SystemConfig

BRANCHES = ("person_absent", "unreachable", "no_confirmation", "activity_missed")
RESIDENT = "maria"

# Boxes left on the living-room floor around the couch: low enough to see Maria over them,
# too wide for the robot to get within speaking distance.
CLUTTER = [
    {
        "name": "boxes_front",
        "height": 0.4,
        "polygon": [[5.6, 1.1], [8.2, 1.1], [8.2, 2.1], [5.6, 2.1]],
    },
    {
        "name": "boxes_side",
        "height": 0.4,
        "polygon": [[5.3, 0.1], [5.95, 0.1], [5.95, 1.1], [5.3, 1.1]],
    },
]


@dataclass(frozen=True)
class HydrationOptions:
    seed: int = 1
    lang: str = "en"
    branch: str | None = None
    live: bool = False
    speed: float | None = None
    config_path: str | None = None
    timeout_s: float = 900.0


def scenario_config(opts: HydrationOptions) -> SystemConfig:
    """The default system configuration plus this scenario's household and triggers."""
    if opts.branch is not None and opts.branch not in BRANCHES:
        raise ConfigError(f"unknown branch '{opts.branch}' (choices: {', '.join(BRANCHES)})")
    check_language(opts.lang)
    data = base_config_data(opts.config_path, opts.seed)
    script: dict[str, Any] = {}
    resident: dict[str, Any] = {
        "name": RESIDENT,
        "language": opts.lang,
        "at": "couch_left",
        "posture": "sitting_couch",
        "activity": "play_phone",
        "script": script,
    }
    sim = data.setdefault("sim", {})
    if opts.branch == "person_absent":
        resident["present"] = False
    elif opts.branch == "unreachable":
        sim["obstacles"] = [*sim.get("obstacles", []), *CLUTTER]
    elif opts.branch == "no_confirmation":
        script["hydration_reminder"] = {"reply": "silence"}
        script["postpone_question"] = {"reply": "confirm"}
    elif opts.branch == "activity_missed":
        resident["skeleton_occluded"] = True
    sim["residents"] = [resident, *[r for r in sim.get("residents", []) if r["name"] != RESIDENT]]
    env = data.setdefault("environment", {})
    sensors = env.setdefault("sensors", {})
    sensors.setdefault(
        "changes", [{"at_s": 3.0, "room": "living_room", "sensor": "temperature", "value": 31.5}]
    )
    env.setdefault(
        "rules",
        [
            {
                "name": "hot_room",
                "sensor": "temperature",
                "above": 28.0,
                "kind": "hydration",
                "user": RESIDENT,
                "priority": 5,
            }
        ],
    )
    return SystemConfig.model_validate(data)


def run_hydration(opts: HydrationOptions) -> dict[str, Any]:
    """Run the scenario to the end of the hydration behaviour; returns the contract's report."""

    def finished(system: System) -> bool:
        runs = [r for r in system.engine.runs.values() if r.name == "hydration"]
        return bool(runs) and runs[0].done and not system.notifications.runs

    done = run_scenario(
        scenario_config(opts),
        finished,
        live=opts.live,
        speed=opts.speed,
        timeout_s=opts.timeout_s,
    )
    system, recorder = done.system, done.recorder
    runs = [r for r in system.engine.runs.values() if r.name == "hydration"]
    run = runs[0] if runs else None
    return {
        "scenario": "hydration",
        "outcome": run.outcome if run and run.done else "timeout",
        "branch": opts.branch or "default",
        "seed": opts.seed,
        "lang": opts.lang,
        "hearing": system.dialogue.hearing,
        **done.timing(),
        "steps": [r.to_dict() for r in run.records] if run else [],
        "acks": [{"id": a.id, "status": a.status, "ts": a.ts} for a in recorder.acks],
        "collisions": system.require_sim("the hydration report").robot.collisions,
        "events": recorder.events,
    }
