"""Fixtures of the environment tests: a real mosquitto broker and MQTT peers, a real
PostgreSQL server, and the health store's database on each backend."""

from collections.abc import Callable
from pathlib import Path

import pytest
from env_broker import broker, peer_factory
from env_postgres import postgres_server

__all__ = ["broker", "database_url", "peer_factory", "postgres_server"]


@pytest.fixture(params=["sqlite", "postgresql"])
def database_url(request: pytest.FixtureRequest, tmp_path: Path) -> str:
    """A fresh, empty health database: an SQLite file, or a PostgreSQL database."""
    if request.param == "sqlite":
        return f"sqlite:///{tmp_path / 'health.db'}"
    new_database: Callable[[], str] = request.getfixturevalue("postgres_server")
    return new_database()
