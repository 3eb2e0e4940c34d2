"""Liveness across processes: heartbeats, a watchdog, and notifications owed to the carers.

Every robot-side and edge process publishes a :class:`Heartbeat`; the cloud's
:class:`Watchdog` raises ``node_lost`` / ``node_back`` events on ``/amiro/events`` when
one stops and comes back.  The :class:`NotificationLedger` keeps each notification until it
is acknowledged, with the latest checkpoint of the behaviour answering it (the edge's
``behavior_checkpoint`` events), and re-sends the pending ones with their checkpoints when
the edge comes back: the restarted edge resumes each behaviour at the task that was running
(at-least-once delivery; at-least-once execution of that one task).  With a
:class:`~amiro.deploy.ledger_store.LedgerStore` the ledger also outlives the cloud: a restarted
cloud loads it and re-sends the pending notifications when it first hears the edge.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any

from amiro.behavior.checkpoint import with_checkpoint
from amiro.core import names
from amiro.core.messages import Acknowledgement, BehaviorEvent, Notification
from amiro.core.node import Node
from amiro.deploy.boundary import Heartbeat
from amiro.deploy.ledger_store import LedgerFile, LedgerStore


class HeartbeatNode(Node):
    def __init__(self, process: str, period_s: float = 1.0) -> None:
        super().__init__("heartbeat")
        self.process = process
        self.period = period_s

    def on_start(self) -> None:
        self.pub = self.create_publisher(names.HEARTBEAT, Heartbeat)
        self._beat()
        self.create_timer(self.period, self._beat)

    def _beat(self) -> None:
        self.pub.publish(Heartbeat(self.process, self.now(), os.getpid()))


@dataclass
class Peer:
    last_seen: float
    pid: int
    alive: bool = True
    lost: int = 0


class Watchdog(Node):
    """Declares a process lost after ``timeout_s`` without heartbeat (clock time)."""

    def __init__(self, watched: dict[str, float], check_s: float = 0.5) -> None:
        super().__init__("watchdog")
        self.watched = watched
        self.check_s = check_s
        self.peers: dict[str, Peer] = {}

    def on_start(self) -> None:
        self.events = self.create_publisher(names.EVENTS, BehaviorEvent)
        self.create_subscription(names.HEARTBEAT, Heartbeat, self._on_beat, depth=50)
        self.create_timer(self.check_s, self._check)

    def _on_beat(self, beat: Heartbeat) -> None:
        if beat.node not in self.watched:
            return
        peer = self.peers.get(beat.node)
        if peer is None:
            self.peers[beat.node] = Peer(self.now(), beat.pid)
            self._event("node_up", beat.node, pid=beat.pid)
            return
        peer.last_seen = self.now()
        if not peer.alive or peer.pid != beat.pid:
            peer.alive = True
            peer.pid = beat.pid
            self._event("node_back", beat.node, pid=beat.pid)

    def _check(self) -> None:
        for name, peer in self.peers.items():
            if peer.alive and self.now() - peer.last_seen > self.watched[name]:
                peer.alive = False
                peer.lost += 1
                self._event("node_lost", name, silent_s=round(self.now() - peer.last_seen, 2))

    def _event(self, kind: str, node: str, **detail: object) -> None:
        self.log.warning("%s: %s", kind, node)
        self.events.publish(BehaviorEvent(self.now(), kind, detail={"node": node, **detail}))


class NotificationLedger(Node):
    """Remembers unacknowledged notifications and their behaviours' latest checkpoints;
    re-sends them, each with its checkpoint, when ``edge`` comes up (late) or back;
    ``store`` (optional) keeps them on disk through every change."""

    def __init__(
        self, edge: str = "edge", resend_delay_s: float = 1.0, store: LedgerStore | None = None
    ) -> None:
        super().__init__("redelivery")  # the environment's ledger is "notification_ledger"
        self.edge = edge
        self.resend_delay_s = resend_delay_s
        self.store = store
        self.pending: dict[str, Notification] = {}
        self.checkpoints: dict[str, dict[str, Any]] = {}
        self.resent = 0
        self.restored = 0  # pending notifications loaded from the store at start

    def on_start(self) -> None:
        if self.store is not None:
            saved = self.store.load()
            self.pending, self.checkpoints = dict(saved.pending), dict(saved.checkpoints)
            self.restored = len(self.pending)
            if self.restored:
                self.log.warning("restored %d pending notification(s)", self.restored)
        self.pub = self.create_publisher(names.NOTIFICATIONS, Notification)
        self.events = self.create_publisher(names.EVENTS, BehaviorEvent)
        self.create_subscription(names.NOTIFICATIONS, Notification, self._on_note, depth=100)
        self.create_subscription(names.ACK, Acknowledgement, self._on_ack, depth=100)
        self.create_subscription(names.EVENTS, BehaviorEvent, self._on_event, depth=1000)

    def _on_note(self, note: Notification) -> None:
        if note.id not in self.pending:
            self.pending[note.id] = note
            self._save()

    def _on_ack(self, ack: Acknowledgement) -> None:
        if ack.id in self.pending:
            self.pending.pop(ack.id)
            self.checkpoints.pop(ack.id, None)
            self._save()

    def _on_event(self, event: BehaviorEvent) -> None:
        if event.type == "behavior_checkpoint":
            ident, checkpoint = event.detail.get("id"), event.detail.get("checkpoint")
            # Kept as sent: the edge that resumes from it validates it.
            if isinstance(ident, str) and ident in self.pending and isinstance(checkpoint, dict):
                self.checkpoints[ident] = checkpoint
                self._save()
        elif event.type in ("node_up", "node_back") and event.detail.get("node") == self.edge:
            # Up: what was raised before the edge listened (a slow start) was lost; back: a
            # restarted edge.  Give its subscriptions a moment to be discovered; a note it
            # did get is dropped there as a duplicate of the running behaviour.
            self.call_later(self.resend_delay_s, self._resend)

    def _resend(self) -> None:
        for note in list(self.pending.values()):
            checkpoint = self.checkpoints.get(note.id)
            self.resent += 1
            detail = {
                "id": note.id,
                "resume_task": None if checkpoint is None else checkpoint.get("task"),
            }
            self.events.publish(
                BehaviorEvent(self.now(), "notification_redelivered", detail=detail)
            )
            self.pub.publish(note if checkpoint is None else with_checkpoint(note, checkpoint))

    def _save(self) -> None:
        if self.store is not None:
            self.store.save(LedgerFile(pending=self.pending, checkpoints=self.checkpoints))

    def persistence(self) -> dict[str, Any]:
        """For the process's report: the store's file and what happened to it, if any."""
        if self.store is None:
            return {}
        return {
            "ledger": {
                "path": str(self.store.path),
                "restored": self.restored,
                "corrupt": self.store.corrupt,
                "write_errors": self.store.write_errors,
            }
        }
