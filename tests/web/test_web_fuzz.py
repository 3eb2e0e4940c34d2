"""10,000 fuzzed web requests from a signed-in client: none crashes the server, all counted."""

from __future__ import annotations

import asyncio
import json

import httpx
import numpy as np
import pytest
from fastapi import FastAPI
from web_served import PASSWORD, Running

ROUTES = [
    ("POST", "/api/chat"),
    ("POST", "/api/tasks"),
    ("POST", "/api/scenarios"),
    ("POST", "/api/devices"),
    ("POST", "/api/sensors"),
    ("GET", "/api/health/{}/{}"),
    ("GET", "/api/notifications?limit={}"),
    ("POST", "/auth/login"),
]
VALUES: list[object] = [
    None,
    True,
    -1,
    0,
    10**12,
    1e308,
    "",
    "x" * 600,
    "kitchen",
    "lights",
    "on",
    "Say",
    "hydration",
    "en",
    "de",
    [],
    {},
    {"a": 1},
    "../../etc/passwd",
    "<script>",
    "'; DROP TABLE",
]
KEYS = [
    "text",
    "lang",
    "type",
    "params",
    "priority",
    "name",
    "user",
    "room",
    "device",
    "state",
    "sensor",
    "value",
    "password",
    "extra",
]


def fuzz_body(rng: np.random.Generator) -> str | bytes:
    kind = rng.integers(4)
    if kind == 0:
        return bytes(rng.integers(0, 256, size=int(rng.integers(0, 64)), dtype=np.uint8))
    if kind == 1:
        return '{"text": "unterminated'
    body = {
        str(rng.choice(KEYS)): VALUES[int(rng.integers(len(VALUES)))]
        for _ in range(int(rng.integers(0, 5)))
    }
    return json.dumps(body)


async def fuzz(app: FastAPI, n: int, rng: np.random.Generator) -> dict[int, int]:
    statuses: dict[int, int] = {}
    transport = httpx.ASGITransport(app=app)
    async with httpx.AsyncClient(transport=transport, base_url="http://testserver") as client:
        res = await client.post("/auth/login", json={"user": "admin", "password": PASSWORD})
        headers = {"X-CSRF-Token": res.json()["csrf"], "Content-Type": "application/json"}
        for _ in range(n):
            method, template = ROUTES[int(rng.integers(len(ROUTES)))]
            args = [
                str(VALUES[int(rng.integers(len(VALUES)))])[:50].replace("/", "%2F")
                for _ in range(2)
            ]
            url = template.format(*args)
            if method == "GET":
                res = await client.get(url)
            else:
                res = await client.post(url, content=fuzz_body(rng), headers=headers)
            statuses[res.status_code] = statuses.get(res.status_code, 0) + 1
        assert (await client.get("/api/state")).status_code == 200  # still serving
    return statuses


@pytest.mark.slow
@pytest.mark.parametrize("running", [1.0], indirect=True)  # a calm home: the server is measured
def test_ten_thousand_fuzzed_requests(running: Running) -> None:
    app = running.served.app
    stats = app.state.stats
    n = 10_000
    statuses = asyncio.run(fuzz(app, n, np.random.default_rng(7)))
    assert stats["requests"] == n + 2
    assert not any(code >= 500 for code in statuses), statuses
    assert sum(c for s, c in statuses.items() if 400 <= s < 500) > n // 2
