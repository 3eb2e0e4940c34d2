"""A real PostgreSQL server for the tests: a throwaway cluster on a free loopback port.

``scripts/test`` installs Debian's postgresql.  The server refuses to run as root, so
under root the cluster belongs to the ``postgres`` account the package creates.
"""

from __future__ import annotations

import itertools
import os
import pwd
import shutil
import subprocess
import tempfile
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest
from env_broker import free_port

_databases = itertools.count()


def _bin_dir() -> Path:
    found = sorted(Path("/usr/lib/postgresql").glob("*/bin/initdb"))
    if not found:
        raise RuntimeError("PostgreSQL is not installed (scripts/test installs it with apt-get)")
    return found[-1].parent


def _as_server_user(cmd: list[str]) -> list[str]:
    return ["runuser", "-u", "postgres", "--", *cmd] if os.geteuid() == 0 else cmd


@pytest.fixture(scope="session")
def postgres_server() -> Iterator[Callable[[], str]]:
    """Yields a factory of fresh, empty databases (SQLAlchemy URLs) on one server."""
    bin_dir, port = _bin_dir(), free_port()
    root = Path(tempfile.mkdtemp(prefix="amiro-pg-"))
    data = root / "data"
    if os.geteuid() == 0:
        account = pwd.getpwnam("postgres")
        os.chown(root, account.pw_uid, account.pw_gid)

    def run(*cmd: str) -> None:
        program = [str(bin_dir / cmd[0]), *cmd[1:]]
        subprocess.run(_as_server_user(program), check=True, capture_output=True, text=True)

    run("initdb", "-D", str(data), "-U", "amiro", "--auth=trust", "-E", "UTF8")
    run(
        "pg_ctl", "-D", str(data), "-w", "-l", str(root / "server.log"),
        "-o", f"-p {port} -k {root} -c listen_addresses=127.0.0.1 -c fsync=on",
        "start",
    )  # fmt: skip

    def new_database() -> str:
        name = f"health_{next(_databases)}"
        run("createdb", "-h", "127.0.0.1", "-p", str(port), "-U", "amiro", name)
        return f"postgresql+psycopg://amiro@127.0.0.1:{port}/{name}"

    try:
        yield new_database
    finally:
        run("pg_ctl", "-D", str(data), "-m", "fast", "-w", "stop")
        shutil.rmtree(root, ignore_errors=True)
