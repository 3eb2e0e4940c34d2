"""What the robot says and the log shows about plans: phrases per language, narration."""

from __future__ import annotations

import pytest

from amiro.behavior.planning.dispatch import CLEAR_REQUEST, OPEN_DOOR_REQUEST, plan_graph
from amiro.behavior.planning.explain import describe_plan
from amiro.behavior.planning.planner import PlanStep
from amiro.behavior.planning.problem import RobotState
from amiro.behavior.planning.topology import topology_from_world
from amiro.core.config import ConfigError
from amiro.dialogue.phrases import phrase
from amiro.home.household import LANGUAGES
from amiro.home.world import World, default_home_path
from amiro.scenarios.deliver_notification import DeliveryOptions, run_delivery
from amiro.scenarios.recorder import narrate
from amiro.sim import door_help

STEPS = [
    PlanStep("move", ("robot_start", "living_door_hallway")),
    PlanStep("ask_open_door", ("john", "living_door", "living_door_hallway")),
    PlanStep("cross", ("living_door", "living_door_hallway", "living_door_living_room")),
    PlanStep("approach", ("maria", "living_door_living_room")),
    PlanStep("deliver", ("maria",)),
]


def test_requests_are_phrases_in_every_language_and_their_key_is_the_act() -> None:
    assert door_help.OPEN_DOOR_REQUEST == OPEN_DOOR_REQUEST  # what the simulated John answers
    for key in (OPEN_DOOR_REQUEST, CLEAR_REQUEST):
        texts = {phrase(key, lang, {"name": "John"}) for lang in LANGUAGES}
        assert len(texts) == len(LANGUAGES) and all(t.startswith("John") for t in texts)


def test_the_plan_behaviour_asks_in_the_blackboard_language() -> None:
    topo = topology_from_world(World.load(default_home_path()))
    graph = plan_graph(STEPS, topo, RobotState("hallway", 0.8, 1.0), "p", 5, {"lang": "fr"})
    say = graph.tasks["a1_ask_open_door"].task.params["steps"][0]["params"]
    assert say["act"] == OPEN_DOOR_REQUEST and say["to"] == "john" and say["lang"] == "fr"
    assert say["text"] == phrase(OPEN_DOOR_REQUEST, "fr", {"name": "John"})


def test_plans_and_replans_read_as_sentences() -> None:
    summary = describe_plan(STEPS)
    assert (
        summary
        == "ask John to open living_door → go through living_door → go to Maria → tell Maria"
    )
    plan = {
        "t": 11.2,
        "type": "plan",
        "number": 2,
        "engine": "pyperplan",
        "planning_ms": 9.5,
        "steps": [str(s) for s in STEPS],
        "summary": summary,
    }
    assert narrate(plan) == f"[   11.2s] Plan 2 (pyperplan, 9.5 ms): {summary}"
    replan = {"t": 11.1, "type": "replan", "reason": "door living_door is closed (seen on the way)"}
    assert narrate(replan).endswith("Re-planning: door living_door is closed (seen on the way)")
    failed = {"t": 40.0, "type": "plan_failed", "explanation": "maria is in living_room, ..."}
    assert narrate(failed).endswith("No plan: maria is in living_room, ...")
    assert narrate({"t": 1.0, "type": "plan_completed", "plans": 2}).endswith("(2 plan(s))")


@pytest.mark.parametrize(
    ("opts", "message"),
    [(DeliveryOptions(lang="de"), "unknown language"), (DeliveryOptions(speed=0.0), "--speed")],
)
def test_bad_options_are_one_line_errors(opts: DeliveryOptions, message: str) -> None:
    with pytest.raises(ConfigError, match=message):
        run_delivery(opts)
