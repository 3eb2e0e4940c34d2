"""The notification ledger: every notification and acknowledgement, persisted.

A notification is stored as ``pending`` when it appears on the bus and closed by its
acknowledgement; on the first start of a process the ledger publishes the still-pending
ones again, so a restart loses none.  Acknowledgements are kept as a log as well.
"""

from __future__ import annotations

from typing import Any

from sqlalchemy import Integer, String, func, insert, select, update
from sqlalchemy.exc import IntegrityError
from sqlalchemy.orm import Mapped, Session, mapped_column

from amiro.core import names
from amiro.core.messages import Acknowledgement, Notification
from amiro.core.node import Node
from amiro.environment.health_store import Base, open_engine


class NotificationRow(Base):
    __tablename__ = "notifications"
    id: Mapped[str] = mapped_column(String(80), primary_key=True)
    user: Mapped[str] = mapped_column(String(40))
    kind: Mapped[str] = mapped_column(String(40))
    priority: Mapped[int] = mapped_column(Integer)
    reason: Mapped[str] = mapped_column(String(500))
    received: Mapped[str] = mapped_column(String(40))
    status: Mapped[str] = mapped_column(String(20), index=True)
    acked: Mapped[str | None] = mapped_column(String(40), nullable=True)


class AckRow(Base):
    __tablename__ = "acknowledgements"
    seq: Mapped[int] = mapped_column(Integer, primary_key=True, autoincrement=True)
    id: Mapped[str] = mapped_column(String(80), index=True)
    status: Mapped[str] = mapped_column(String(20))
    ts: Mapped[str] = mapped_column(String(40))


class NotificationLedger:
    def __init__(self, url: str | None = None) -> None:
        self.engine = open_engine(url)

    def record(self, note: Notification, received: str) -> bool:
        """Store a new notification as pending; False if its id is already known."""
        row = {
            "id": note.id,
            "user": note.user,
            "kind": note.kind,
            "priority": note.priority,
            "reason": note.reason[:500],
            "received": received,
            "status": "pending",
        }
        try:
            with self.engine.begin() as conn:
                conn.execute(insert(NotificationRow), [row])
        except IntegrityError:
            return False
        return True

    def acknowledge(self, ack: Acknowledgement) -> None:
        with self.engine.begin() as conn:
            conn.execute(insert(AckRow), [{"id": ack.id, "status": ack.status, "ts": ack.ts}])
            conn.execute(
                update(NotificationRow)
                .where(NotificationRow.id == ack.id)
                .values(status=ack.status, acked=ack.ts)
            )

    def pending(self) -> list[Notification]:
        """Notifications not yet acknowledged, oldest first."""
        query = select(NotificationRow).where(NotificationRow.status == "pending")
        with Session(self.engine) as session:
            rows = session.scalars(query.order_by(NotificationRow.received))
            return [self._note(r) for r in rows]

    @staticmethod
    def _note(r: NotificationRow) -> Notification:
        return Notification(r.id, r.user, r.kind, r.priority, reason=r.reason)

    def recent(self, limit: int = 50) -> list[dict[str, Any]]:
        with Session(self.engine) as session:
            query = select(NotificationRow).order_by(NotificationRow.received.desc()).limit(limit)
            return [
                {
                    "id": r.id,
                    "user": r.user,
                    "kind": r.kind,
                    "priority": r.priority,
                    "reason": r.reason,
                    "received": r.received,
                    "status": r.status,
                    "acked": r.acked,
                }
                for r in session.scalars(query)
            ]

    def ack_count(self) -> int:
        with self.engine.connect() as conn:
            return int(conn.execute(select(func.count()).select_from(AckRow)).scalar_one())


class LedgerNode(Node):
    def __init__(self, ledger: NotificationLedger) -> None:
        super().__init__("notification_ledger")
        self.ledger = ledger
        self._replayed = False

    def on_start(self) -> None:
        pub = self.create_publisher(names.NOTIFICATIONS, Notification)
        self.create_subscription(names.NOTIFICATIONS, Notification, self._on_note, 10_000)
        self.create_subscription(names.ACK, Acknowledgement, self.ledger.acknowledge, 10_000)
        if not self._replayed:  # once per process, not on a supervisor restart
            self._replayed = True
            for note in self.ledger.pending():
                self.log.info("replaying pending notification %s", note.id)
                pub.publish(note)

    def _on_note(self, note: Notification) -> None:
        self.ledger.record(note, self.runtime.clock.iso(self.now()))
