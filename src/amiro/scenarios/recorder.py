"""Records what a scenario did, for the live log and the contract's JSON report."""

from __future__ import annotations

import sys
from collections.abc import Callable
from typing import Any, TextIO

from amiro.core import names
from amiro.core.messages import Acknowledgement, BehaviorEvent
from amiro.core.runtime import Runtime


class EventRecorder:
    """Collects behaviour events, notifications and acknowledgements in order."""

    def __init__(self, runtime: Runtime, live: TextIO | None = None) -> None:
        self.runtime = runtime
        self.events: list[dict[str, Any]] = []
        self.acks: list[Acknowledgement] = []
        self.live = live
        bus = runtime.bus
        bus.subscribe(names.EVENTS, BehaviorEvent, self._on_event, depth=10_000)
        bus.subscribe(names.ACK, Acknowledgement, self.acks.append, depth=1000)

    def _add(self, event: dict[str, Any]) -> None:
        self.events.append(event)
        if self.live is not None:
            self.live.write(narrate(event) + "\n")
            self.live.flush()

    def _on_event(self, ev: BehaviorEvent) -> None:
        self._add(ev.to_dict())


def _details(detail: dict[str, Any]) -> str:
    shown = ", ".join(f"{k}: {v}" for k, v in detail.items() if v not in (None, "", {}, []))
    return f" ({shown})" if shown else ""


def _task_line(ev: dict[str, Any]) -> str:
    return _details({k: v for k, v in ev.items() if k not in ("t", "type", "graph", "task")})


_NARRATION: dict[str, Callable[[dict[str, Any]], str]] = {
    "notification": lambda e: (
        f"Alert: {e.get('reason') or e.get('kind')} → {e.get('kind')} reminder for {e.get('user')}"
    ),
    "graph_submitted": lambda e: (
        f"Behaviour {e.get('graph')} queued (priority {e.get('priority')})"
    ),
    "graph_suspended": lambda e: f"Behaviour {e.get('graph')} put aside for {e.get('by')}",
    "graph_resumed": lambda e: f"Behaviour {e.get('graph')} resumes",
    "task_started": lambda e: f"  ▶ {e.get('task_type')} [{e.get('task')}]",
    "task_finished": lambda e: (
        f"  {'✔' if e.get('result') == 'success' else '✘'} "
        f"{e.get('task_type')} {e.get('result')}{_details(e.get('detail') or {})}"
    ),
    "task_preempted": lambda e: f"  ⏸ {e.get('task')} preempted by a more urgent behaviour",
    "graph_finished": lambda e: f"Behaviour {e.get('graph')} finished: {e.get('outcome')}",
    "say": lambda e: f"    robot says ({e.get('lang')}): “{e.get('text')}”",
    "heard": lambda e: (
        f"    heard {e.get('speaker') or 'someone'}: “{e.get('text')}” → {e.get('intent')}"
    ),
    "person_found": lambda e: f"    found {e.get('person')} in the {e.get('room')}",
    "search_room": lambda e: f"    not seen here; going to look in the {e.get('room')}",
    "activity_recognised": lambda e: f"    saw {e.get('person')} {e.get('activity')}",
    "ack": lambda e: f"    acknowledged {e.get('id')} to the smart home: {e.get('status')}",
    "plan": lambda e: (
        f"Plan {e.get('number')} ({e.get('engine')}, {e.get('planning_ms')} ms): "
        f"{e.get('summary') or ', '.join(e.get('steps') or [])}"
    ),
    "replan": lambda e: f"Re-planning: {e.get('reason')}",
    "plan_failed": lambda e: f"No plan: {e.get('explanation')}",
    "plan_completed": lambda e: f"Errand completed ({e.get('plans')} plan(s))",
}


def narrate(ev: dict[str, Any]) -> str:
    """One readable line for a person following the robot live."""
    fmt = _NARRATION.get(str(ev.get("type")))
    body = fmt(ev) if fmt else f"{ev.get('type')}{_task_line(ev)}"
    return f"[{ev.get('t', 0.0):7.1f}s] {body}"


def stdout_or_none(enabled: bool) -> TextIO | None:
    return sys.stdout if enabled else None
