"""Nodes: the unit of lifecycle and supervision.

A node creates its publishers, subscriptions, timers, services and action servers in
:meth:`Node.on_start`; the runtime tracks them so that stopping (or restarting after a crash)
removes them all.  A node never reads wall time: ``self.now()`` is the runtime's clock.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypeVar

from amiro.core.bus import ActionServer, Publisher, Subscription

if TYPE_CHECKING:
    from amiro.core.runtime import Runtime, Timer

M = TypeVar("M")


class Node:
    """Base class of every amiro node (sim robot, navigation, behaviour engine, ...)."""

    def __init__(self, name: str) -> None:
        self.name = name
        self.log = logging.getLogger(f"amiro.{name}")
        self._runtime: Runtime | None = None
        self._subscriptions: list[Subscription[Any]] = []
        self._timers: list[Timer] = []
        self._services: list[str] = []
        self._actions: list[str] = []
        self.running = False
        self.restarts = 0

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.name}>"

    # --- lifecycle, overridden by subclasses ----------------------------------------------
    def on_start(self) -> None:
        """Create publishers, subscriptions, timers; called on start and on every restart."""

    def on_stop(self) -> None:
        """Release what on_start acquired beyond bus resources (files, devices)."""

    # --- used by the runtime ------------------------------------------------------------
    def attach(self, runtime: Runtime) -> None:
        self._runtime = runtime

    def start(self) -> None:
        if self.running:
            return
        self.running = True
        self.on_start()

    def stop(self) -> None:
        if not self.running:
            return
        self.running = False
        try:
            self.on_stop()
        finally:
            self._release()

    def _release(self) -> None:
        rt = self.runtime
        for sub in self._subscriptions:
            sub.destroy()
        for timer in self._timers:
            timer.cancel()
        for name in self._services:
            rt.bus.remove_service(name)
        for name in self._actions:
            rt.bus.remove_action_server(name)
        self._subscriptions.clear()
        self._timers.clear()
        self._services.clear()
        self._actions.clear()

    # --- helpers for subclasses ------------------------------------------------------------
    @property
    def runtime(self) -> Runtime:
        if self._runtime is None:
            raise RuntimeError(f"node {self.name} is not attached to a runtime")
        return self._runtime

    def now(self) -> float:
        return self.runtime.clock.now()

    def create_publisher(self, topic: str, msg_type: type[M]) -> Publisher[M]:
        return self.runtime.bus.publisher(topic, msg_type)

    def create_subscription(
        self, topic: str, msg_type: type[M], callback: Callable[[M], None], depth: int = 10
    ) -> Subscription[M]:
        sub = self.runtime.bus.subscribe(topic, msg_type, callback, depth, owner=self)
        self._subscriptions.append(sub)
        return sub

    def create_timer(self, period: float, callback: Callable[[], None]) -> Timer:
        timer = self.runtime.create_timer(period, callback, owner=self)
        self._timers.append(timer)
        return timer

    def call_later(self, delay: float, callback: Callable[[], object]) -> Timer:
        """A one-shot timer, released with the node like every other resource."""
        timer = self.runtime.call_later(delay, callback, owner=self)
        self._timers.append(timer)
        return timer

    def create_service(self, name: str, handler: Callable[[Any], Any]) -> None:
        self.runtime.bus.create_service(name, handler, owner=self)
        self._services.append(name)

    def create_action_server(self, name: str, server: ActionServer[Any, Any, Any]) -> None:
        self.runtime.bus.create_action_server(name, server)
        self._actions.append(name)
