"""NotifyEnvironment: acknowledge a notification to the smart environment / health platform."""

from __future__ import annotations

from typing import Literal

from amiro.behavior.task import Task, TaskContext, TaskParams, TaskStatus
from amiro.core import names
from amiro.core.messages import Acknowledgement

AckStatus = Literal["done", "postponed", "failed"]


class NotifyEnvironment(Task):
    """params: ``id`` (default blackboard ``notification_id``), ``status`` (done, postponed,
    failed).  The blackboard's ``acked`` records that the behaviour has answered."""

    type_name = "NotifyEnvironment"

    class Params(TaskParams):
        id: str | None = None
        status: AckStatus = "done"

    def start(self, ctx: TaskContext) -> None:
        p = self.bind(ctx, self.Params)
        status = p.status
        ident = p.id if p.id is not None else str(ctx.blackboard.get("notification_id", ""))
        clock = ctx.need(ctx.modules.clock, "clock")
        ack = Acknowledgement(id=ident, status=status, ts=clock.iso(ctx.now()))
        ctx.bus.publish(names.ACK, ack)
        ctx.blackboard["acked"] = status
        self.detail = {"id": ident, "status": status}
        ctx.event("ack", id=ident, status=status)

    def update(self, ctx: TaskContext) -> TaskStatus:
        return TaskStatus.SUCCESS
