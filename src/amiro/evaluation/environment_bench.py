"""Speed of the smart environment: MQTT through the bridge, the web API, health queries.

Rates on this machine, never pass/fail.  The MQTT figure needs a broker (``mqtt_url``);
the health figure fills a SQLite file with a year of per-minute heart rate for 20 users.
"""

from __future__ import annotations

import asyncio
import json
import tempfile
from datetime import date, timedelta
from pathlib import Path
from typing import Any

import httpx
import numpy as np
import paho.mqtt.client as mqtt
from paho.mqtt.enums import CallbackAPIVersion
from pydantic import SecretStr
from sqlalchemy import insert

from amiro.core.clock import SimClock, wall_seconds
from amiro.core.runtime import Runtime
from amiro.environment.health_store import HealthStore, MeasurementRow, day_number
from amiro.environment.mqtt_bridge import MqttBridgeNode, MqttConfig, parse_url

YEAR_START = date(2025, 7, 15)


def bench_mqtt(url: str, messages: int = 20_000) -> float:
    """Sensor messages per second from a publisher, through the broker, onto the bus."""
    rt = Runtime(SimClock())
    bridge = rt.add(MqttBridgeNode(MqttConfig(url=url, client_id="amiro-bench"), "home", []))
    rt.start()
    deadline = wall_seconds() + 10
    while not bridge.connected and wall_seconds() < deadline:
        rt.spin_for(0.05)
    host, port = parse_url(url)
    pub = mqtt.Client(callback_api_version=CallbackAPIVersion.VERSION2)
    pub.connect(host, port)
    pub.loop_start()
    payload = json.dumps({"value": 22.5, "unit": "C"}).encode()
    started = wall_seconds()
    for _ in range(messages):
        pub.publish("amiro/home/kitchen/temperature", payload, qos=0)
    while bridge.counts["sensor"] < messages and wall_seconds() - started < 120:
        rt.spin_for(0.05)
    elapsed = wall_seconds() - started
    pub.disconnect()
    pub.loop_stop()
    rt.stop()
    return bridge.counts["sensor"] / elapsed


def fill_year(store: HealthStore, users: int, rng: np.random.Generator) -> int:
    """A year of per-minute heart rate for ``users`` users, inserted in bulk."""
    start = day_number(YEAR_START) * 86400.0
    minutes = 365 * 24 * 60
    ts = start + 60.0 * np.arange(minutes)
    days = (ts // 86400).astype(int)
    total = 0
    with store.engine.begin() as conn:
        for u in range(users):
            values = 70 + 8 * rng.standard_normal(minutes)
            for lo in range(0, minutes, 100_000):
                hi = min(lo + 100_000, minutes)
                rows = [
                    {
                        "user": f"user{u:02d}",
                        "metric": "heart_rate",
                        "ts": float(t),
                        "day": int(d),
                        "value": float(v),
                        "value2": None,
                    }
                    for t, d, v in zip(ts[lo:hi], days[lo:hi], values[lo:hi], strict=True)
                ]
                conn.execute(insert(MeasurementRow), rows)
                total += len(rows)
    return total


def bench_health(
    store: HealthStore, users: int, rng: np.random.Generator, n: int = 300
) -> dict[str, float]:
    """Queries per second of latest, yesterday and a 7-day trend, random user and day."""
    out: dict[str, float] = {}
    for name in ("latest", "yesterday", "trend_7d"):
        started = wall_seconds()
        for _ in range(n):
            user = f"user{int(rng.integers(users)):02d}"
            day = YEAR_START + timedelta(days=int(rng.integers(8, 364)))
            if name == "latest":
                store.latest(user, "heart_rate")
            elif name == "yesterday":
                store.yesterday(user, "heart_rate", day)
            else:
                store.trend(user, "heart_rate", day, 7)
        out[name] = round(n / (wall_seconds() - started), 1)
    return out


def bench_web(requests: int = 2000) -> dict[str, float]:
    """Authenticated GET /api/state and a health query, in process (no network)."""
    from amiro.web.config import WebConfig
    from amiro.web.served import assemble, load_serve_config

    cfg = load_serve_config(None)
    web = WebConfig(
        admin_password=SecretStr("bench"), api_token=SecretStr("bench-token"), demo_data=False
    )
    served = assemble(type(cfg)(cfg.system, web), SimClock())
    served.system.start()
    served.runtime.spin_for(1.0)

    async def run(path: str, spin: bool) -> float:
        transport = httpx.ASGITransport(app=served.app)
        headers = {"Authorization": "Bearer bench-token"}
        async with httpx.AsyncClient(
            transport=transport, base_url="http://b", headers=headers
        ) as c:
            started = wall_seconds()
            for _ in range(requests):
                if spin:  # a health query is answered on the runtime's thread
                    task = asyncio.create_task(c.get(path))
                    while not task.done():
                        served.gateway.inbox.drain()
                        await asyncio.sleep(0)
                    task.result().raise_for_status()
                else:
                    (await c.get(path)).raise_for_status()
            return requests / (wall_seconds() - started)

    state = asyncio.run(run("/api/state", False))
    health = asyncio.run(run("/api/health/maria/heart_rate?days=7", True))
    served.stop()
    return {"state_rps": round(state, 1), "health_rps": round(health, 1)}


def bench_env(mqtt_url: str | None, users: int = 20, seed: int = 1) -> dict[str, Any]:
    rng = np.random.default_rng(seed)
    result: dict[str, Any] = {
        "mqtt_msgs_per_s": round(bench_mqtt(mqtt_url), 1) if mqtt_url else None
    }
    result["web"] = bench_web()
    with tempfile.TemporaryDirectory() as tmp:
        store = HealthStore(f"sqlite:///{Path(tmp) / 'year.db'}")
        started = wall_seconds()
        rows = fill_year(store, users, rng)
        result["health_rows"] = rows
        result["health_fill_s"] = round(wall_seconds() - started, 1)
        result["health_queries_per_s"] = bench_health(store, users, rng)
        store.close()
    return result
