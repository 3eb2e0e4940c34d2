"""The dashboard API with a signed-in session: state, behaviours, smart home, health, chat."""

from __future__ import annotations

import time
from collections.abc import Callable

from fastapi.testclient import TestClient
from web_served import Running, login, start_served

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


def test_a_fall_from_the_dashboard_preempts_a_running_hydration(
    client: TestClient, running: Running
) -> None:
    headers = {"X-CSRF-Token": login(client)}
    scenarios = client.get("/api/behaviours").json()["scenarios"]
    assert scenarios["fall"] == 100 and scenarios["hydration"] == 5  # the behaviours' own
    engine = running.served.system.engine
    res = client.post(
        "/api/scenarios", json={"name": "hydration", "user": "maria"}, headers=headers
    )
    assert res.json()["priority"] == 5
    wait_for(lambda: (engine.current() or {}).get("name") == "hydration")
    res = client.post("/api/scenarios", json={"name": "fall", "user": "maria"}, headers=headers)
    assert res.status_code == 200 and res.json()["priority"] == 100
    wait_for(lambda: (engine.current() or {}).get("name") == "fall")
    assert "hydration" in [q["name"] for q in engine.queue_snapshot()]  # put aside
    # The dashboard's state is a snapshot published by the runtime: it follows the engine.
    wait_for(lambda: (client.get("/api/state").json()["current"] or {}).get("name") == "fall")
    state = client.get("/api/state").json()
    assert state["current"]["name"] == "fall" and state["current"]["priority"] == 100
    gateway = running.served.gateway
    now = gateway.call(gateway.robot.state).result(5)["current"]  # one moment of the runtime
    run = engine.runs[now["graph"]]
    assert [s["task"] for s in now["progress"]["done"]] == [r.task_id for r in run.records]
    following = run.graph.tasks[now["task"]].on_success  # a task id, or End
    assert [s["task"] for s in now["progress"]["ahead"][:1]] == (
        [following] if isinstance(following, str) else []
    )
    explicit = {"name": "hydration", "user": "maria", "priority": 7}
    assert client.post("/api/scenarios", json=explicit, headers=headers).json()["priority"] == 7


def test_emergency_stop_lidar_and_doors(client: TestClient, running: Running) -> None:
    headers = {"X-CSRF-Token": login(client)}
    assert client.post("/api/estop", json={"engaged": True}, headers=headers).status_code == 200
    wait_for(lambda: client.get("/api/state").json()["estop"] is True)
    client.post("/api/estop", json={"engaged": False}, headers=headers)
    wait_for(lambda: client.get("/api/state").json()["estop"] is False)
    home = running.served.system.world.home
    wait_for(lambda: len(client.get("/api/scan").json()["points"]) > 50)
    points = client.get("/api/scan?most=40").json()["points"]
    assert 10 <= len(points) <= 40
    assert all(
        -0.5 <= x <= home.size[0] + 0.5 and -0.5 <= y <= home.size[1] + 0.5 for x, y in points
    )
    doors = client.get("/api/state").json()["doors"]
    assert doors == {d.name: d.open for d in home.doors}
    world = running.served.system.world
    running.served.gateway.call(lambda: world.set_door("kitchen_door", False)).result(5)
    wait_for(lambda: client.get("/api/state").json()["doors"]["kitchen_door"] is False)


BAD_INPUT: list[tuple[str, str, dict[str, object] | None]] = [
    ("POST", "/api/scenarios", {"name": "hydration", "priority": 101}),
    ("POST", "/api/scenarios", {"name": "hydration", "priority": "high"}),
    ("POST", "/api/scenarios", {"name": "dance"}),
    ("POST", "/api/estop", {}),
    ("POST", "/api/estop", {"engaged": "yes"}),
    ("POST", "/api/estop", {"engaged": True, "why": "x"}),
    ("GET", "/api/scan?most=5", None),
    ("GET", "/api/scan?most=lots", None),
    ("GET", "/api/health/maria/steps?days=0", None),
    ("GET", "/api/health/maria/steps?days=400", None),
    ("GET", "/api/health/maria/weight", None),
]


def test_bad_input_is_a_422_with_one_line(client: TestClient) -> None:
    headers = {"X-CSRF-Token": login(client)}  # one served system for every case
    for method, path, body in BAD_INPUT:
        res = client.request(method, path, json=body, headers=headers)
        assert res.status_code == 422, (method, path, body, res.text)
        assert "\n" not in res.json()["detail"], (path, body)
    assert client.post("/api/estop", json={"engaged": True}).status_code == 403  # no CSRF


def test_health_charts_carry_units_ranges_and_the_demo_mark(client: TestClient) -> None:
    login(client)
    users = client.get("/api/health/users").json()
    assert users["demo"] is False and users["users"] == []  # the tests' served app: no demo
    bp = client.get("/api/health/maria/blood_pressure").json()
    assert bp["unit"] == "mmHg" and bp["series"] == ["systolic", "diastolic"]
    assert bp["ranges"]["diastolic"] == [60, 80] and bp["demo"] is False


def test_demo_health_data_is_seeded_and_marked() -> None:
    demo = start_served(demo=True)
    try:
        with TestClient(demo.served.app) as client:
            login(client)
            users = client.get("/api/health/users").json()
            assert users["demo"] is True and users["users"] == ["maria"]
            bp = client.get("/api/health/maria/blood_pressure?days=14").json()
            assert bp["demo"] is True and all(d["count"] == 2 for d in bp["days"][:-1])
            clock = demo.served.runtime.clock
            assert bp["latest"]["ts"] <= clock.iso(clock.now())  # nothing in the future
            assert all(d["mean2"] < d["mean"] for d in bp["days"])  # diastolic below systolic
    finally:
        demo.loop.stop()
        demo.served.stop()


def wait_for(check: Callable[[], bool], timeout: float = 20.0) -> None:
    deadline = time.monotonic() + timeout
    while not check():
        assert time.monotonic() < deadline, "timed out"
        time.sleep(0.05)
