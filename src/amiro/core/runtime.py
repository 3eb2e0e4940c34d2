"""The runtime: one clock, one bus, the nodes, their timers and their supervisor.

The executor is single-threaded and event-driven: it delivers pending bus messages, then
moves the clock to the earliest timer deadline and fires it.  Ties break by creation order,
so a seeded simulation replays identically.  A callback that raises is reported to the
:class:`Supervisor`, which logs it and restarts the node; the process never goes down.
"""

from __future__ import annotations

import heapq
import itertools
import logging
import random
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TypeVar

import numpy as np

from amiro.core.bus import Bus
from amiro.core.clock import Clock, SimClock
from amiro.core.node import Node

log = logging.getLogger("amiro.runtime")

NodeT = TypeVar("NodeT", bound=Node)


@dataclass(order=True)
class Timer:
    due: float
    seq: int
    period: float = field(compare=False)
    callback: Callable[[], object] = field(compare=False)  # its return value is ignored
    owner: object | None = field(compare=False, default=None)
    active: bool = field(compare=False, default=True)

    def cancel(self) -> None:
        self.active = False


@dataclass
class NodeHealth:
    failures: int = 0
    restarts: int = 0
    failed_permanently: bool = False
    last_error: str = ""


class Supervisor:
    """Restarts a node whose callback raised; gives up (stops it) after ``max_restarts``."""

    def __init__(self, runtime: Runtime, max_restarts: int = 5) -> None:
        self.runtime = runtime
        self.max_restarts = max_restarts
        self.health: dict[str, NodeHealth] = {}
        self.listeners: list[Callable[[Node, BaseException, NodeHealth], None]] = []

    def report(self, owner: object | None, exc: BaseException) -> None:
        if not isinstance(owner, Node):
            log.error("callback raised outside any node: %r", exc, exc_info=exc)
            return
        health = self.health.setdefault(owner.name, NodeHealth())
        health.failures += 1
        health.last_error = f"{type(exc).__name__}: {exc}"
        log.error("node %s raised %s", owner.name, health.last_error, exc_info=exc)
        try:
            owner.stop()
        except Exception as stop_exc:  # a broken on_stop must not block the restart
            log.error("node %s failed to stop cleanly: %r", owner.name, stop_exc)
            owner.running = False
        if health.restarts >= self.max_restarts:
            health.failed_permanently = True
            log.error("node %s stopped for good after %d restarts", owner.name, health.restarts)
        else:
            health.restarts += 1
            owner.restarts = health.restarts
            try:
                owner.start()
            except Exception as start_exc:
                health.failed_permanently = True
                log.error("node %s could not restart: %r", owner.name, start_exc)
                try:  # release what the failed on_start acquired (timers would keep firing)
                    owner.stop()
                except Exception:
                    owner.running = False
        for listener in self.listeners:
            listener(owner, exc, health)


class Runtime:
    """Owns the clock, the bus, the nodes and the timers; runs them deterministically."""

    def __init__(self, clock: Clock | None = None, seed: int = 0, max_restarts: int = 5) -> None:
        self.clock: Clock = clock if clock is not None else SimClock()
        self.seed = seed
        self.rng = np.random.default_rng(seed)
        self.random = random.Random(seed)
        self.supervisor = Supervisor(self, max_restarts)
        self.bus = Bus(on_error=self.supervisor.report)
        self.nodes: dict[str, Node] = {}
        self._timers: list[Timer] = []
        self._seq = itertools.count()
        self.started = False

    # --- nodes ----------------------------------------------------------------------------
    def add(self, node: NodeT) -> NodeT:
        if node.name in self.nodes:
            raise ValueError(f"a node named {node.name} is already in the runtime")
        node.attach(self)
        self.nodes[node.name] = node
        if self.started:
            self._start_node(node)
        return node

    def node(self, name: str) -> Node:
        return self.nodes[name]

    def start(self) -> None:
        self.started = True
        for node in list(self.nodes.values()):
            self._start_node(node)

    def _start_node(self, node: Node) -> None:
        try:
            node.start()
        except Exception as exc:
            self.supervisor.report(node, exc)

    def stop(self) -> None:
        for node in reversed(list(self.nodes.values())):
            try:
                node.stop()
            except Exception as exc:
                log.error("node %s failed to stop: %r", node.name, exc)
        self.started = False

    # --- timers ---------------------------------------------------------------------------
    def create_timer(
        self, period: float, callback: Callable[[], None], owner: object | None = None
    ) -> Timer:
        """A periodic timer (``period`` > 0); first fires one period from now."""
        if period <= 0:
            raise ValueError(f"timer period must be positive, got {period}")
        timer = Timer(self.clock.now() + period, next(self._seq), period, callback, owner)
        heapq.heappush(self._timers, timer)
        return timer

    def call_later(
        self, delay: float, callback: Callable[[], object], owner: object | None = None
    ) -> Timer:
        """A one-shot timer."""
        timer = Timer(self.clock.now() + max(delay, 0.0), next(self._seq), 0.0, callback, owner)
        heapq.heappush(self._timers, timer)
        return timer

    # --- executor -------------------------------------------------------------------------
    def spin_once(self, until: float | None = None) -> bool:
        """Deliver pending messages, then fire the next timer (not later than ``until``).

        Returns False when there is nothing left to do before ``until``.
        """
        if self.bus.pending():
            self.bus.spin_some()
            return True
        while self._timers and not self._timers[0].active:
            heapq.heappop(self._timers)
        if not self._timers:
            return False
        timer = self._timers[0]
        if until is not None and timer.due > until:
            return False
        heapq.heappop(self._timers)
        self.clock.advance_to(timer.due)
        if timer.period > 0:
            timer.due += timer.period  # keeps its seq: ties break by creation order
            heapq.heappush(self._timers, timer)
        else:
            timer.active = False
        try:
            timer.callback()
        except Exception as exc:
            self.supervisor.report(timer.owner, exc)
        self.bus.spin_some()
        return True

    def spin_for(self, duration: float) -> None:
        end = self.clock.now() + duration
        while self.spin_once(until=end):
            pass
        self.clock.advance_to(end)

    def spin_until(self, predicate: Callable[[], bool], timeout: float) -> bool:
        """Run until ``predicate()`` holds (True) or ``timeout`` seconds of clock time pass."""
        end = self.clock.now() + timeout
        while not predicate():
            if not self.spin_once(until=end):
                self.clock.advance_to(end)
                return predicate()
        return True
