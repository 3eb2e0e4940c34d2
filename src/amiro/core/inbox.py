"""A thread-safe door into the single-threaded runtime.

Network threads (paho's loop, the web server) never touch the bus: they post callables here
and a timer of the runtime runs them, so every bus callback stays on the executor's thread.
"""

from __future__ import annotations

import logging
import queue
from collections.abc import Callable

log = logging.getLogger("amiro.inbox")


class Inbox:
    def __init__(self) -> None:
        self._queue: queue.SimpleQueue[Callable[[], None]] = queue.SimpleQueue()
        self.failed = 0

    def post(self, job: Callable[[], None]) -> None:
        """Run ``job`` on the runtime's thread at its next drain (any thread may call this)."""
        self._queue.put(job)

    def pending(self) -> int:
        return self._queue.qsize()

    def drain(self, limit: int = 100_000) -> int:
        """Run posted jobs in order; a job that raises is logged and counted, never fatal."""
        done = 0
        while done < limit:
            try:
                job = self._queue.get_nowait()
            except queue.Empty:
                break
            done += 1
            try:
                job()
            except Exception as exc:
                self.failed += 1
                log.warning("inbox job failed: %r", exc)
        return done
