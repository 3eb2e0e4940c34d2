"""Task types that plan actions need beyond the paper's: a sequence, a door check, a request.

Importing this module registers them.  Each plan action becomes one task of the plan's
behaviour (see :mod:`.dispatch`); the composite ones reuse Say, Listen, Search and MoveTo.
"""

from __future__ import annotations

from amiro.behavior.planning.door_sensing import door_state_from_scan
from amiro.behavior.planning.knowledge import DoorState, KnowledgeBase
from amiro.behavior.task import Task, TaskContext, TaskError, TaskStatus, make_task
from amiro.core import names
from amiro.core.bus import Subscription
from amiro.core.messages import LaserScan


class Sequence(Task):
    """Runs ``steps`` one after the other; fails with the first that fails.

    ``steps`` is data, as in YAML behaviours: a list of ``{type, params}``.
    """

    type_name = "Sequence"
    cancellable = True

    def start(self, ctx: TaskContext) -> None:
        steps = self.params.get("steps")
        if not isinstance(steps, list) or not all(isinstance(s, dict) for s in steps):
            raise TaskError("Sequence: steps must be a list of {type, params}")
        self.todo: list[Task] = [make_task(str(s.get("type")), s.get("params")) for s in steps]
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

    def start(self, ctx: TaskContext) -> None:
        p = self.resolved(ctx)
        kb: KnowledgeBase = ctx.module("knowledge")
        name = str(p["door"])
        if name not in kb.topology.doors:
            raise TaskError(f"CheckDoor: unknown door {name!r}")
        self.door = kb.topology.doors[name]
        self.wait_open = bool(p.get("wait_open", False))
        self.deadline = ctx.now() + float(p.get("timeout_s", 1.0))
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
        pose = ctx.module("navigation").pose
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
