"""Task types that plan actions need beyond the paper's: a sequence, a door check, a request.

Importing this module registers them.  Each plan action becomes one task of the plan's
behaviour (see :mod:`.dispatch`); the composite ones reuse Say, Listen, Search and MoveTo.
"""

from __future__ import annotations

from typing import Any

from pydantic import Field, field_validator

from amiro.behavior.planning.door_sensing import door_state_from_scan
from amiro.behavior.planning.knowledge import DoorState
from amiro.behavior.task import Task, TaskContext, TaskError, TaskParams, TaskStatus, make_task
from amiro.core import names
from amiro.core.bus import Subscription
from amiro.core.messages import LaserScan


class Sequence(Task):
    """Runs ``steps`` one after the other; fails with the first that fails.

    ``steps`` is data, as in YAML behaviours: a list of ``{type, params}``.
    """

    type_name = "Sequence"
    cancellable = True

    class Step(TaskParams):
        type: str
        params: dict[str, Any] | None = None

    class Params(TaskParams):
        steps: list[Sequence.Step]

        @field_validator("steps")
        @classmethod
        def _buildable(cls, steps: list[Sequence.Step]) -> list[Sequence.Step]:
            for step in steps:
                make_task(step.type, step.params)  # a bad step is an error now, not later
            return steps

    def start(self, ctx: TaskContext) -> None:
        steps = self.bind(ctx, self.Params).steps
        self.todo: list[Task] = [make_task(s.type, s.params) for s in steps]
        self.current: Task | None = None
        self.detail = {"done": []}
        self._next(ctx)

    def _next(self, ctx: TaskContext) -> None:
        self.current = self.todo.pop(0) if self.todo else None
        if self.current is not None:
            self.current.start(ctx)

    def update(self, ctx: TaskContext) -> TaskStatus:
        while self.current is not None:
            status = self.current.update(ctx)
            if status is TaskStatus.RUNNING:
                return status
            name = self.current.type_name or type(self.current).__name__
            if status is TaskStatus.FAILURE:
                self.detail.update(failed=name, **self.current.detail)
                return status
            self.detail["done"].append(name)
            self._next(ctx)
        return TaskStatus.SUCCESS

    def cancel(self, ctx: TaskContext) -> None:
        if self.current is not None and type(self.current).cancellable:
            self.current.cancel(ctx)


class CheckDoor(Task):
    """Look at ``door`` with the lidar for up to ``timeout_s``.

    With ``wait_open`` (after asking someone to open it) succeed once it is seen open and
    fail at the timeout; without (before crossing) fail as soon as it is seen closed and
    succeed when seen open or never seen (the crossing will tell).
    """

    type_name = "CheckDoor"
    cancellable = True

    class Params(TaskParams):
        door: str
        wait_open: bool = False
        timeout_s: float = Field(1.0, ge=0)

    def start(self, ctx: TaskContext) -> None:
        p = self.bind(ctx, self.Params)
        kb = ctx.need(ctx.modules.knowledge, "knowledge")
        if p.door not in kb.topology.doors:
            raise TaskError(f"CheckDoor: unknown door {p.door!r}")
        self.door = kb.topology.doors[p.door]
        self.wait_open = p.wait_open
        self.deadline = ctx.now() + p.timeout_s
        self.seen: DoorState | None = None
        self.scans: list[LaserScan] = []
        self.sub: Subscription[LaserScan] | None = ctx.bus.subscribe(
            names.SCAN, LaserScan, self.scans.append, depth=1
        )

    def _close(self) -> None:
        if self.sub is not None:
            self.sub.destroy()
            self.sub = None

    def update(self, ctx: TaskContext) -> TaskStatus:
        pose = ctx.need(ctx.modules.navigation, "navigation").pose
        if self.scans and pose is not None:
            state = door_state_from_scan(self.scans[-1], pose, self.door.a, self.door.b)
            self.scans.clear()
            self.seen = state or self.seen
            self.detail = {"door": self.door.name, "seen": str(self.seen) if self.seen else None}
            if state is DoorState.OPEN:
                self._close()
                return TaskStatus.SUCCESS
            if state is DoorState.CLOSED and not self.wait_open:
                self._close()
                self.detail["reason"] = "door_closed"
                return TaskStatus.FAILURE
        if ctx.now() >= self.deadline:
            self._close()
            if self.wait_open:
                self.detail["reason"] = "door_still_closed"
                return TaskStatus.FAILURE
            return TaskStatus.SUCCESS
        return TaskStatus.RUNNING

    def cancel(self, ctx: TaskContext) -> None:
        self._close()
