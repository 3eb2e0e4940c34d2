"""A database server that is not there: one line naming the URL, not psycopg's paragraph."""

from __future__ import annotations

import socket

import pytest

from amiro.core.config import ConfigError
from amiro.environment.health_store import HealthStore


def test_a_refused_postgresql_connection_is_one_line() -> None:
    with socket.socket() as sock:  # a port nobody listens on
        sock.bind(("127.0.0.1", 0))
        port = sock.getsockname()[1]
    url = f"postgresql://amiro@127.0.0.1:{port}/health"
    with pytest.raises(ConfigError) as err:
        HealthStore(url)
    assert str(err.value).startswith(f"database '{url}': cannot open it: ")
    assert "\n" not in str(err.value) and "refused" in str(err.value)
