"""The dashboard API with a signed-in session: state, behaviours, smart home, health, chat."""

from __future__ import annotations

import time

from fastapi.testclient import TestClient
from web_served import Running, login

from amiro.environment.messages import HealthMeasurement


def test_state_and_map_describe_the_simulated_home(client: TestClient) -> None:
    login(client)
    home = client.get("/api/map").json()
    assert {"living_room", "kitchen", "bedroom"} <= set(home["rooms"])
    state = client.get("/api/state").json()
    assert {"robot", "path", "people", "current", "queue", "transcript"} <= set(state)
    assert [p["name"] for p in state["people"]] == ["maria"]


def test_triggering_a_task_and_a_scenario_queues_behaviours(
    client: TestClient, running: Running
) -> None:
    csrf = login(client)
    headers = {"X-CSRF-Token": csrf}
    beh = client.get("/api/behaviours").json()
    assert "hydration" in beh["scenarios"] and "Say" in beh["task_types"]
    res = client.post("/api/tasks", json={"type": "Say", "params": {"text": "hi"}}, headers=headers)
    assert res.status_code == 200 and res.json()["run"] == "web_say#1"
    bad = client.post("/api/tasks", json={"type": "Fly"}, headers=headers)
    assert bad.status_code == 422 and "unknown task type" in bad.json()["detail"]
    res = client.post(
        "/api/scenarios", json={"name": "hydration", "user": "maria"}, headers=headers
    )
    ident = res.json()["id"]
    engine = running.served.system.engine
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline and not any(
        r.name == "hydration" for r in engine.runs.values()
    ):
        time.sleep(0.05)
    assert any(r.name == "hydration" for r in engine.runs.values())
    notes = client.get("/api/notifications").json()["notifications"]
    assert any(n["id"] == ident and n["kind"] == "hydration" for n in notes)
    unknown = client.post("/api/scenarios", json={"name": "dance"}, headers=headers)
    assert unknown.status_code == 422


def test_device_command_changes_the_reported_state(client: TestClient, running: Running) -> None:
    headers = {"X-CSRF-Token": login(client)}
    first = client.get("/api/state").json()["devices"]  # known before any command
    assert first["kitchen"] == {"lights": "off", "blinds": "close"}
    res = client.post(
        "/api/devices", json={"room": "kitchen", "device": "lights", "state": "on"}, headers=headers
    )
    assert res.status_code == 200
    deadline = time.monotonic() + 5
    state: dict[str, object] = {}
    while time.monotonic() < deadline:
        state = client.get("/api/state").json()
        if state["devices"].get("kitchen", {}).get("lights") == "on":
            break
        time.sleep(0.05)
    assert state["devices"]["kitchen"]["lights"] == "on"
    assert state["sensors"]["kitchen"]["luminosity"] > 250
    wrong = client.post(
        "/api/devices", json={"room": "garage", "device": "lights", "state": "on"}, headers=headers
    )
    assert wrong.status_code == 422


def test_health_chart_data_and_a_chat_answered_from_the_store(
    client: TestClient, running: Running
) -> None:
    headers = {"X-CSRF-Token": login(client)}
    store = running.served.system.environment.health
    store.add_many(
        [
            HealthMeasurement("maria", "heart_rate", 60.0 + d, f"2026-07-{d:02d}T09:00:00+00:00")
            for d in range(5, 15)
        ]
    )
    data = client.get("/api/health/maria/heart_rate?days=10").json()
    assert data["direction"] == "rising" and data["latest"]["value"] == 74.0
    assert len(data["days"]) == 10
    assert client.get("/api/health/maria/mood").status_code == 422
    assert client.get("/api/health/Robert');--/steps").status_code in (404, 422)
    text = "care a fost pulsul meu ieri"  # the simulated day is 2026-07-15
    body = {"text": text, "lang": "ro", "user": "maria"}
    reply = client.post("/api/chat", json=body, headers=headers)
    assert reply.status_code == 200 and "74" in reply.json()["reply"]
    assert reply.json()["user"] == "maria"
    own = client.post("/api/chat", json={"text": "what is my heart rate"}, headers=headers).json()
    assert own["user"] == "admin" and "no measurement" in own["reply"]  # admin has no data
    assert (
        client.post("/api/chat", json={"text": "hi", "lang": "de"}, headers=headers).status_code
        == 422
    )
    bad_user = {"text": "hi", "user": "Robert');--"}
    assert client.post("/api/chat", json=bad_user, headers=headers).status_code == 422
    transcript = client.get("/api/state").json()["transcript"]
    deadline = time.monotonic() + 5
    while time.monotonic() < deadline and not any(m["who"] == "maria" for m in transcript):
        time.sleep(0.05)
        transcript = client.get("/api/state").json()["transcript"]
    assert any(m["who"] == "maria" and m["text"] == text for m in transcript)
