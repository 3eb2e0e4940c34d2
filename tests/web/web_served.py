"""A served system (simulated home, environment, gateway, app) with its runtime spinning."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import pytest
from fastapi.testclient import TestClient
from pydantic import SecretStr

from amiro.core.clock import SimClock
from amiro.web.config import WebConfig
from amiro.web.served import RuntimeLoop, Served, assemble, load_serve_config

PASSWORD = "correct horse battery staple"
TOKEN = "test-token-0123456789"


@dataclass
class Running:
    served: Served
    loop: RuntimeLoop


def start_served(speed: float = 20.0, demo: bool = False) -> Running:
    """The default household; ``demo``: with the seeded demo health data of ``amiro serve``
    (off by default: tests add the measurements they check)."""
    cfg = load_serve_config(None)
    web = WebConfig(
        admin_password=SecretStr(PASSWORD), api_token=SecretStr(TOKEN), port=0, demo_data=demo
    )
    served = assemble(type(cfg)(cfg.system, web), SimClock(speed=speed))
    served.system.start()
    loop = RuntimeLoop(served.runtime)
    loop.start()
    return Running(served, loop)


@pytest.fixture
def running(request: pytest.FixtureRequest) -> Iterator[Running]:
    r = start_served(getattr(request, "param", 20.0))
    yield r
    r.loop.stop()
    r.served.stop()


@pytest.fixture
def client(running: Running) -> Iterator[TestClient]:
    with TestClient(running.served.app) as c:
        yield c


def login(client: TestClient) -> str:
    res = client.post("/auth/login", json={"user": "admin", "password": PASSWORD})
    assert res.status_code == 200
    return str(res.json()["csrf"])
