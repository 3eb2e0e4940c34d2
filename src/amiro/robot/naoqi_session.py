"""A NAOqi session for amiro: lazy ``qi`` import, cached services, non-blocking calls.

Every call goes out with ``_async=True`` so a slow robot never stalls the runtime (NAOqi's
``say`` returns only when speech ends); :meth:`NaoqiSession.reap`, called from a timer,
logs calls that failed.  ``qi`` is the optional ``pepper`` extra.
"""

from __future__ import annotations

import importlib
import logging
import time
from typing import Any

from amiro.core.config import ConfigError

log = logging.getLogger("amiro.robot.naoqi")


def qi_module() -> Any:
    try:
        return importlib.import_module("qi")
    except ImportError:
        raise ConfigError("Pepper over NAOqi needs qi: pip install 'amiro[pepper]'") from None


class NaoqiSession:
    """One connection to a robot's NAOqi (``tcp://HOST:9559``)."""

    def __init__(self, url: str, session: Any | None = None) -> None:
        self.url = url
        if session is None:
            session = qi_module().Session()
            try:
                session.connect(url)
            except RuntimeError as exc:
                raise ConfigError(f"cannot reach NAOqi at {url}: {exc}") from None
        self.session = session
        self._services: dict[str, Any] = {}
        self._pending: list[tuple[str, Any]] = []
        self.calls = 0
        self.errors = 0

    def service(self, name: str) -> Any:
        if name not in self._services:
            try:
                self._services[name] = self.session.service(name)
            except RuntimeError as exc:
                raise ConfigError(f"NAOqi at {self.url} has no {name}: {exc}") from None
        return self._services[name]

    def call(self, service: str, method: str, *args: Any) -> None:
        """Start ``service.method(*args)`` without waiting for it."""
        future = getattr(self.service(service), method)(*args, _async=True)
        self._pending.append((f"{service}.{method}", future))
        self.calls += 1

    def query(self, service: str, method: str, *args: Any) -> Any:
        """Start a call whose result is wanted later: the future (``isFinished``, ``value``)."""
        self.calls += 1
        return getattr(self.service(service), method)(*args, _async=True)

    def reap(self) -> int:
        """Forget finished calls, logging failures; returns how many are still running."""
        running = []
        for what, future in self._pending:
            if not future.isFinished():
                running.append((what, future))
            elif future.hasError():
                self.errors += 1
                log.warning("NAOqi %s failed: %s", what, future.error())
        self._pending = running
        return len(running)

    def close(self, grace_s: float = 2.0) -> None:
        """Disconnect once the calls still running have finished (at most ``grace_s``), so
        the last commands, such as stopping the base, reach the robot."""
        deadline = time.monotonic() + grace_s
        for _, future in self._pending:
            left_ms = int((deadline - time.monotonic()) * 1000)
            if left_ms <= 0:
                break
            future.wait(left_ms)
        self.reap()
        self.session.close()
