"""``amiro run deliver-notification`` end to end: re-planning when a door is found closed."""

from __future__ import annotations

import json
from typing import Any

from amiro.scenarios.deliver_notification import DeliveryOptions, run_delivery


def types(report: dict[str, Any]) -> list[str]:
    return [e["type"] for e in report["events"]]


def test_door_found_closed_robot_replans_asks_for_help_and_delivers() -> None:
    rep = run_delivery(DeliveryOptions())
    assert rep["outcome"] == "completed"
    assert {"scenario", "outcome", "sim_time_s", "wall_time_s", "steps", "events"} <= rep.keys()
    assert any("replan" in t for t in types(rep))
    first = rep["learned"][0]
    assert first["fact"] == "door living_door" and first["value"] == "closed"
    assert first["source"] == "lidar"  # learned from the sensor, not the simulator's state
    ids = [s["id"] for s in rep["steps"] if s["result"] == "success"]
    assert [i.split("_", 1)[1] for i in ids] == [
        "move",
        "ask_open_door",
        "cross",
        "approach",
        "deliver",
    ]
    assert rep["collisions"] == 0
    json.dumps(rep)


def test_every_way_closed_and_no_help_ends_without_a_plan_and_says_why() -> None:
    rep = run_delivery(
        DeliveryOptions(closed_doors=("living_door", "kitchen_living_door"), help=False)
    )
    assert rep["outcome"] == "no_plan"
    assert "living_door is closed" in rep["explanation"]
    assert "kitchen_living_door is closed" in rep["explanation"]
    assert types(rep).count("replan") >= 2
    assert types(rep)[-1] != "plan_completed"


def test_check_activity_after_delivering_in_romanian() -> None:
    rep = run_delivery(DeliveryOptions(closed_doors=(), lang="ro", check_activity="play_phone"))
    assert rep["outcome"] == "completed" and rep["replans"] == 0
    assert rep["plans"][0]["steps"][-1]["action"] == "check_activity"
    said = [e["text"] for e in rep["events"] if e["type"] == "say"]
    assert said == ["Maria, a sunat fiica dumneavoastră: vă vizitează în după-amiaza aceasta."]
    seen = [e for e in rep["events"] if e["type"] == "activity_recognised"]
    assert seen and seen[0]["activity"] == "play_phone"
