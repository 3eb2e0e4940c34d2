"""Handlers: turn an event (smart home, voice command, web trigger) into a behaviour.

As in the paper, a handler builds the task graph that answers one kind of event; the
registry maps the event kind to that factory and submits the graph to the engine.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from amiro.behavior.engine import BehaviorEngine, GraphRun
from amiro.behavior.graph import TaskGraph
from amiro.behavior.loader import load_behavior

HandlerFactory = Callable[[dict[str, Any]], TaskGraph]


class HandlerError(ValueError):
    """An event no handler knows, or a payload its handler cannot use."""


class HandlerRegistry:
    """Event kind -> graph factory; :meth:`handle` builds and submits the behaviour."""

    def __init__(self, engine: BehaviorEngine) -> None:
        self.engine = engine
        self._factories: dict[str, HandlerFactory] = {}

    def register(self, kind: str, factory: HandlerFactory, *, replace: bool = False) -> None:
        if not kind:
            raise HandlerError("a handler needs a non-empty event kind")
        if kind in self._factories and not replace:
            raise HandlerError(f"a handler for '{kind}' is already registered")
        self._factories[kind] = factory

    def handler(self, kind: str) -> Callable[[HandlerFactory], HandlerFactory]:
        """Decorator form of :meth:`register`."""

        def deco(factory: HandlerFactory) -> HandlerFactory:
            self.register(kind, factory)
            return factory

        return deco

    def kinds(self) -> list[str]:
        return sorted(self._factories)

    def __contains__(self, kind: object) -> bool:
        return kind in self._factories

    def build(self, kind: str, payload: Mapping[str, Any] | None = None) -> TaskGraph:
        factory = self._factories.get(kind)
        if factory is None:
            known = ", ".join(self.kinds()) or "none"
            raise HandlerError(f"no handler for event kind '{kind}' (known: {known})")
        try:
            graph = factory(dict(payload or {}))
        except KeyError as exc:
            raise HandlerError(f"handler '{kind}': payload lacks {exc}") from None
        if not isinstance(graph, TaskGraph):
            raise HandlerError(f"handler '{kind}' returned {type(graph).__name__}, not a TaskGraph")
        return graph

    def handle(self, kind: str, payload: Mapping[str, Any] | None = None) -> GraphRun:
        """Build the behaviour for this event and submit it to the engine."""
        return self.engine.submit(self.build(kind, payload))


def yaml_handler(path: str | Path) -> HandlerFactory:
    """A factory loading a YAML behaviour, with the payload overriding its blackboard.

    The file is loaded once here too, so a mistake in it (a misspelt task parameter) is a
    ConfigError when the handler is made, at start-up, not when its first event comes."""
    load_behavior(path)

    def factory(payload: dict[str, Any]) -> TaskGraph:
        return load_behavior(path, overrides=payload)

    return factory
