"""The in-process bus with ROS 2 semantics: topics, services and actions.

Topics deliver through bounded per-subscription queues (like a KEEP_LAST history): a slow
subscriber loses its oldest messages, counted in ``dropped``, and never blocks a publisher.
Delivery happens when the executor spins, in publication order per subscription, so a
callback that publishes never re-enters another callback.  Services are synchronous calls.
Actions carry a goal, feedback, a result and cancellation through :class:`GoalHandle`.
"""

from __future__ import annotations

import enum
import logging
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Generic, TypeVar

log = logging.getLogger("amiro.bus")

M = TypeVar("M")
Req = TypeVar("Req")
Res = TypeVar("Res")
G = TypeVar("G")
F = TypeVar("F")
R = TypeVar("R")

ErrorHook = Callable[[object | None, BaseException], None]


class BusError(RuntimeError):
    """A misuse of the bus: a type clash on a topic, an unknown service or action."""


@dataclass
class TopicStats:
    published: int = 0
    delivered: int = 0
    dropped: int = 0
    rejected: int = 0


class Subscription(Generic[M]):
    def __init__(
        self, bus: Bus, topic: str, callback: Callable[[M], None], depth: int, owner: object | None
    ) -> None:
        self.bus = bus
        self.topic = topic
        self.callback = callback
        self.owner = owner
        self.queue: deque[M] = deque(maxlen=depth)
        self.dropped = 0
        self.active = True

    def push(self, msg: M) -> None:
        if len(self.queue) == self.queue.maxlen:
            self.dropped += 1
            self.bus.stats(self.topic).dropped += 1
        was_empty = not self.queue
        self.queue.append(msg)
        if was_empty:
            self.bus._ready.append(self)

    def destroy(self) -> None:
        self.active = False
        self.queue.clear()
        self.bus._remove_subscription(self)


class Publisher(Generic[M]):
    def __init__(self, bus: Bus, topic: str, msg_type: type[M]) -> None:
        self.bus = bus
        self.topic = topic
        self.msg_type = msg_type

    def publish(self, msg: M) -> None:
        self.bus.publish(self.topic, msg)


class GoalStatus(enum.Enum):
    EXECUTING = "executing"
    SUCCEEDED = "succeeded"
    ABORTED = "aborted"
    CANCELED = "canceled"
    REJECTED = "rejected"

    @property
    def done(self) -> bool:
        return self is not GoalStatus.EXECUTING


class GoalHandle(Generic[G, F, R]):
    """One goal of an action, shared by client and server (in-process, no copies)."""

    _next_id = 0

    def __init__(self, action: str, goal: G) -> None:
        GoalHandle._next_id += 1
        self.id = GoalHandle._next_id
        self.action = action
        self.goal = goal
        self.status = GoalStatus.EXECUTING
        self.feedback: F | None = None
        self.result: R | None = None
        self.cancel_requested = False
        self._feedback_cbs: list[Callable[[F], None]] = []
        self._done_cbs: list[Callable[[GoalHandle[G, F, R]], None]] = []
        self._cancel_cb: Callable[[GoalHandle[G, F, R]], None] | None = None

    # client side
    def on_feedback(self, cb: Callable[[F], None]) -> None:
        self._feedback_cbs.append(cb)

    def on_done(self, cb: Callable[[GoalHandle[G, F, R]], None]) -> None:
        if self.status.done:
            cb(self)
        else:
            self._done_cbs.append(cb)

    def cancel(self) -> None:
        """Ask the server to stop; it answers with ``canceled`` (or finishes first)."""
        if self.status.done or self.cancel_requested:
            return
        self.cancel_requested = True
        if self._cancel_cb is not None:
            self._cancel_cb(self)

    @property
    def done(self) -> bool:
        return self.status.done

    # server side
    def publish_feedback(self, feedback: F) -> None:
        self.feedback = feedback
        for cb in list(self._feedback_cbs):
            cb(feedback)

    def succeed(self, result: R) -> None:
        self._finish(GoalStatus.SUCCEEDED, result)

    def abort(self, result: R) -> None:
        self._finish(GoalStatus.ABORTED, result)

    def canceled(self, result: R) -> None:
        self._finish(GoalStatus.CANCELED, result)

    def reject(self, result: R) -> None:
        """Refuse a goal after it was handed on (a remote server said no)."""
        self._finish(GoalStatus.REJECTED, result)

    def _finish(self, status: GoalStatus, result: R) -> None:
        if self.status.done:
            return
        self.status = status
        self.result = result
        for cb in self._done_cbs:
            cb(self)
        self._done_cbs.clear()


class ActionServer(Generic[G, F, R]):
    """Implemented by a node: accept goals, drive them (usually from a timer), honour cancel."""

    def accept(self, goal: G) -> bool:
        return True

    def execute(self, handle: GoalHandle[G, F, R]) -> None:
        raise NotImplementedError

    def cancel(self, handle: GoalHandle[G, F, R]) -> None:
        """Default: stop at once.  Servers that need to wind down override this."""
        handle.canceled(self.canceled_result(handle))

    def canceled_result(self, handle: GoalHandle[G, F, R]) -> R:
        raise NotImplementedError


@dataclass
class _Service:
    handler: Callable[[Any], Any]
    owner: object | None


@dataclass
class _Topic:
    msg_type: type
    subscriptions: list[Subscription[Any]] = field(default_factory=list)


class Bus:
    """Topics, services and actions inside one process."""

    def __init__(self, on_error: ErrorHook | None = None) -> None:
        self._topics: dict[str, _Topic] = {}
        self._stats: dict[str, TopicStats] = {}
        self._services: dict[str, _Service] = {}
        self._actions: dict[str, ActionServer[Any, Any, Any]] = {}
        self._ready: deque[Subscription[Any]] = deque()
        self.on_error: ErrorHook = on_error or _log_error

    # --- topics -----------------------------------------------------------------------
    def _topic(self, name: str, msg_type: type) -> _Topic:
        topic = self._topics.get(name)
        if topic is None:
            topic = self._topics[name] = _Topic(msg_type)
        elif topic.msg_type is not msg_type:
            raise BusError(
                f"topic {name} carries {topic.msg_type.__name__}, not {msg_type.__name__}"
            )
        return topic

    def stats(self, name: str) -> TopicStats:
        st = self._stats.get(name)
        if st is None:
            st = self._stats[name] = TopicStats()
        return st

    def publisher(self, name: str, msg_type: type[M]) -> Publisher[M]:
        self._topic(name, msg_type)
        return Publisher(self, name, msg_type)

    def subscribe(
        self,
        name: str,
        msg_type: type[M],
        callback: Callable[[M], None],
        depth: int = 10,
        owner: object | None = None,
    ) -> Subscription[M]:
        if depth < 1:
            raise BusError(f"queue depth must be at least 1, got {depth}")
        sub: Subscription[M] = Subscription(self, name, callback, depth, owner)
        self._topic(name, msg_type).subscriptions.append(sub)
        return sub

    def publish(self, name: str, msg: object) -> None:
        topic = self._topics.get(name)
        if topic is None:
            topic = self._topic(name, type(msg))
        if not isinstance(msg, topic.msg_type):
            self.stats(name).rejected += 1
            raise BusError(
                f"topic {name} carries {topic.msg_type.__name__}, got {type(msg).__name__}"
            )
        self.stats(name).published += 1
        for sub in topic.subscriptions:
            sub.push(msg)

    def _remove_subscription(self, sub: Subscription[Any]) -> None:
        topic = self._topics.get(sub.topic)
        if topic is not None and sub in topic.subscriptions:
            topic.subscriptions.remove(sub)

    def pending(self) -> bool:
        return bool(self._ready)

    def spin_some(self, max_callbacks: int = 100_000) -> int:
        """Deliver queued messages until the bus is quiet; returns how many were delivered."""
        delivered = 0
        while self._ready and delivered < max_callbacks:
            sub = self._ready.popleft()
            while sub.queue and sub.active:
                msg = sub.queue.popleft()
                delivered += 1
                self.stats(sub.topic).delivered += 1
                try:
                    sub.callback(msg)
                except Exception as exc:  # a callback never takes the bus down
                    self.on_error(sub.owner, exc)
                    break
            if sub.queue and sub.active:
                self._ready.append(sub)
        return delivered

    # --- services -------------------------------------------------------------------------
    def create_service(
        self, name: str, handler: Callable[[Req], Res], owner: object | None = None
    ) -> None:
        if name in self._services:
            raise BusError(f"service {name} is already provided")
        self._services[name] = _Service(handler, owner)

    def remove_service(self, name: str) -> None:
        self._services.pop(name, None)

    def has_service(self, name: str) -> bool:
        return name in self._services

    def call(self, name: str, request: object) -> Any:
        service = self._services.get(name)
        if service is None:
            raise BusError(f"no service named {name}")
        return service.handler(request)

    # --- actions --------------------------------------------------------------------------
    def create_action_server(self, name: str, server: ActionServer[G, F, R]) -> None:
        if name in self._actions:
            raise BusError(f"action {name} is already provided")
        self._actions[name] = server

    def remove_action_server(self, name: str) -> None:
        self._actions.pop(name, None)

    def has_action(self, name: str) -> bool:
        return name in self._actions

    def accepts(self, name: str, goal: Any) -> bool:
        """Whether the server of ``name`` would accept ``goal``: its ``accept`` only, nothing
        runs (a bridge answers a goal request from another process with it)."""
        server = self._actions.get(name)
        return server is not None and server.accept(goal)

    def send_goal(self, name: str, goal: G) -> GoalHandle[G, Any, Any]:
        server = self._actions.get(name)
        if server is None:
            raise BusError(f"no action server named {name}")
        handle: GoalHandle[G, Any, Any] = GoalHandle(name, goal)
        if not server.accept(goal):
            handle.status = GoalStatus.REJECTED
            return handle
        handle._cancel_cb = server.cancel
        server.execute(handle)
        return handle

    def topics(self) -> dict[str, str]:
        return {name: t.msg_type.__name__ for name, t in sorted(self._topics.items())}


def _log_error(owner: object | None, exc: BaseException) -> None:
    log.error("callback of %s raised %r", owner, exc, exc_info=exc)
