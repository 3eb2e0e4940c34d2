"""NotifyEnvironment: acknowledge a notification to the smart environment / health platform."""

from __future__ import annotations

from amiro.behavior.task import Task, TaskContext, TaskStatus
from amiro.core import names
from amiro.core.messages import Acknowledgement

ACK_STATUSES = ("done", "postponed", "failed")


class NotifyEnvironment(Task):
    """params: ``id`` (default blackboard ``notification_id``), ``status`` (done, postponed,
    failed).  The blackboard's ``acked`` records that the behaviour has answered."""

    type_name = "NotifyEnvironment"

    def start(self, ctx: TaskContext) -> None:
        p = self.resolved(ctx)
        status = str(p.get("status", "done"))
        if status not in ACK_STATUSES:
            raise ValueError(f"NotifyEnvironment: status must be one of {ACK_STATUSES}")
        ident = str(p.get("id", ctx.blackboard.get("notification_id", "")))
        clock = ctx.module("clock")
        ack = Acknowledgement(id=ident, status=status, ts=clock.iso(ctx.now()))
        ctx.bus.publish(names.ACK, ack)
        ctx.blackboard["acked"] = status
        self.detail = {"id": ident, "status": status}
        ctx.event("ack", id=ident, status=status)

    def update(self, ctx: TaskContext) -> TaskStatus:
        return TaskStatus.SUCCESS
