"""Small task types and helpers shared by the behaviour tests."""

from __future__ import annotations

from typing import Any, ClassVar

from amiro.behavior import (
    BehaviorEngine,
    EngineConfig,
    Task,
    TaskContext,
    TaskParams,
    TaskStatus,
)
from amiro.behavior.modules import Modules
from amiro.core.clock import SimClock
from amiro.core.runtime import Runtime

EPS = 1e-6


class FakeWork(Task):
    """Atomic work lasting ``duration`` seconds of clock time; optionally writes a result."""

    type_name = "FakeWork"

    class Params(TaskParams):
        duration: float = 1.0
        succeed: bool = True
        write: str = ""
        value: Any = None

    def __init__(
        self, duration: float | str = 1.0, succeed: bool = True, write: str = "", value: Any = None
    ) -> None:
        super().__init__(duration=duration, succeed=succeed, write=write, value=value)
        self.t0 = 0.0
        self.p: dict[str, Any] = {}

    def start(self, ctx: TaskContext) -> None:
        self.p = self.resolved(ctx)
        self.t0 = ctx.now()

    def update(self, ctx: TaskContext) -> TaskStatus:
        if ctx.now() - self.t0 < float(self.p["duration"]) - EPS:
            return TaskStatus.RUNNING
        if self.p["write"]:
            ctx.blackboard[self.p["write"]] = self.p["value"]
        self.detail["value"] = self.p["value"]
        return TaskStatus.SUCCESS if self.p["succeed"] else TaskStatus.FAILURE


class FakeWait(FakeWork):
    """Like FakeWork but cancellable: a more urgent behaviour may stop it."""

    type_name = "FakeWait"
    cancellable = True
    cancelled_at: ClassVar[list[float]] = []

    def cancel(self, ctx: TaskContext) -> None:
        FakeWait.cancelled_at.append(ctx.now())


class FakeBoom(Task):
    """Raises in start or update; or asks for a module that may not exist."""

    type_name = "FakeBoom"

    class Params(TaskParams):
        where: str = "update"

    def __init__(self, where: str = "update") -> None:
        super().__init__(where=where)

    def start(self, ctx: TaskContext) -> None:
        if self.params["where"] == "start":
            raise RuntimeError("boom in start")
        if self.params["where"] == "module":
            ctx.need(ctx.modules.navigation, "navigation")

    def update(self, ctx: TaskContext) -> TaskStatus:
        raise RuntimeError("boom in update")


def make_engine(
    preemption: bool = True, tick_s: float = 0.05, modules: Modules | None = None
) -> tuple[Runtime, BehaviorEngine]:
    runtime = Runtime(SimClock())
    engine = BehaviorEngine(
        config=EngineConfig(tick_s=tick_s, preemption=preemption), modules=modules
    )
    runtime.add(engine)
    runtime.start()
    return runtime, engine


def order(engine: BehaviorEngine) -> list[tuple[str, str, str]]:
    """(graph run, task id, result) of every record, in order."""
    return [(r.graph, r.task_id, r.result) for r in engine.records]


def run_all(runtime: Runtime, engine: BehaviorEngine, timeout: float = 60.0) -> None:
    assert runtime.spin_until(lambda: engine.idle, timeout), "engine did not become idle"
