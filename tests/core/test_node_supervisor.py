"""Node lifecycle and the supervisor that restarts failing nodes."""

from __future__ import annotations

import logging
from dataclasses import dataclass

import pytest

from amiro.core.bus import ActionServer, GoalHandle
from amiro.core.node import Node
from amiro.core.runtime import NodeHealth, Runtime


@dataclass(frozen=True)
class Num:
    value: int


class Echo(ActionServer[int, int, int]):
    def execute(self, handle: GoalHandle[int, int, int]) -> None:
        handle.succeed(handle.goal)


class Worker(Node):
    """Ticks every second, listens on ``cmd``, offers a service and an action."""

    def __init__(self, name: str, fail_at: set[float] | None = None, fail_on: int = -1) -> None:
        super().__init__(name)
        self.fail_at = fail_at or set()
        self.fail_on = fail_on
        self.starts = 0
        self.stops = 0
        self.ticks: list[float] = []
        self.heard: list[int] = []

    def on_start(self) -> None:
        self.starts += 1
        self.create_subscription("cmd", Num, self.on_cmd)
        self.create_timer(1.0, self.tick)
        self.create_service(f"{self.name}/ping", lambda req: "pong")
        self.create_action_server(f"{self.name}/echo", Echo())

    def on_stop(self) -> None:
        self.stops += 1

    def tick(self) -> None:
        self.ticks.append(self.now())
        if self.now() in self.fail_at:
            raise RuntimeError(f"tick failed at {self.now()}")

    def on_cmd(self, msg: Num) -> None:
        self.heard.append(msg.value)
        if msg.value == self.fail_on:
            raise ValueError(f"cannot handle {msg.value}")


class AlwaysFails(Worker):
    def tick(self) -> None:
        self.ticks.append(self.now())
        raise RuntimeError("broken")


# --- node lifecycle ------------------------------------------------------------------------


def test_stop_releases_everything_and_names_become_free() -> None:
    rt = Runtime()
    node = Worker("w")
    rt.add(node)
    rt.start()
    assert node.running
    assert rt.bus.call("w/ping", None) == "pong"
    assert rt.bus.send_goal("w/echo", 4).result == 4

    node.stop()
    assert not node.running
    assert node.stops == 1
    assert not rt.bus.has_service("w/ping")
    assert not rt.bus.has_action("w/echo")
    rt.bus.create_service("w/ping", lambda req: "other")  # the name is free again
    rt.bus.create_action_server("w/echo", Echo())
    rt.bus.publish("cmd", Num(1))
    rt.spin_for(3.0)
    assert node.ticks == []
    assert node.heard == []

    node.stop()  # stopping twice is harmless
    assert node.stops == 1


def test_restart_by_hand_reacquires() -> None:
    rt = Runtime()
    node = Worker("w")
    rt.add(node)
    rt.start()
    rt.spin_for(1.0)
    node.stop()
    node.start()
    rt.bus.publish("cmd", Num(5))
    rt.spin_for(1.0)
    assert node.heard == [5]
    assert node.ticks == [1.0, 2.0]
    assert rt.bus.call("w/ping", None) == "pong"


def test_runtime_stop_stops_nodes_in_reverse_order() -> None:
    order: list[str] = []

    class Tracked(Node):
        def on_stop(self) -> None:
            order.append(self.name)

    rt = Runtime()
    for name in ("a", "b", "c"):
        rt.add(Tracked(name))
    rt.start()
    rt.stop()
    assert order == ["c", "b", "a"]
    assert not any(n.running for n in rt.nodes.values())


def test_runtime_add() -> None:
    rt = Runtime()
    rt.add(Worker("w"))
    with pytest.raises(ValueError, match="already"):
        rt.add(Worker("w"))
    rt.start()
    late = Worker("late")
    rt.add(late)
    assert late.running  # added to a started runtime: started at once
    assert rt.node("late") is late


def test_unattached_node_has_no_runtime() -> None:
    with pytest.raises(RuntimeError, match="not attached"):
        Node("lonely").now()


# --- supervisor --------------------------------------------------------------------------


def test_failing_timer_restarts_node_without_duplicates(caplog: pytest.LogCaptureFixture) -> None:
    rt = Runtime()
    flaky = Worker("flaky", fail_at={2.0})
    rt.add(flaky)
    steady = Worker("steady")
    rt.add(steady)
    reports: list[tuple[str, str]] = []
    rt.supervisor.listeners.append(lambda n, e, h: reports.append((n.name, str(e))))
    rt.start()

    with caplog.at_level(logging.ERROR, logger="amiro.runtime"):
        rt.spin_for(5.0)

    assert any(
        "flaky" in r.getMessage() and "tick failed" in r.getMessage() for r in caplog.records
    )
    assert reports == [("flaky", "tick failed at 2.0")]
    health = rt.supervisor.health["flaky"]
    assert (health.failures, health.restarts, health.failed_permanently) == (1, 1, False)
    assert "RuntimeError" in health.last_error
    assert flaky.running
    assert (flaky.starts, flaky.stops, flaky.restarts) == (2, 1, 1)
    # old timer released: one tick per second, not two after the restart
    assert flaky.ticks == [1.0, 2.0, 3.0, 4.0, 5.0]
    assert steady.ticks == [1.0, 2.0, 3.0, 4.0, 5.0]
    assert "steady" not in rt.supervisor.health
    # old subscription released: one delivery per message
    rt.bus.publish("cmd", Num(7))
    rt.spin_for(0.5)
    assert flaky.heard == [7]
    assert steady.heard == [7]
    # the service and action were re-created under the same names
    assert rt.bus.call("flaky/ping", None) == "pong"
    assert rt.bus.send_goal("flaky/echo", 2).result == 2


def test_gives_up_after_max_restarts() -> None:
    rt = Runtime(max_restarts=2)
    broken = AlwaysFails("broken")
    rt.add(broken)
    steady = Worker("steady")
    rt.add(steady)
    rt.start()
    rt.spin_for(10.0)

    health = rt.supervisor.health["broken"]
    assert health.failed_permanently
    assert (health.failures, health.restarts) == (3, 2)
    assert not broken.running
    assert broken.starts == 3
    assert broken.ticks == [1.0, 2.0, 3.0]
    assert len(steady.ticks) == 10  # the runtime kept running the others
    assert not rt.bus.has_service("broken/ping")
    assert not rt.bus.has_action("broken/echo")
    rt.bus.publish("cmd", Num(1))
    rt.spin_for(1.0)
    assert broken.heard == []
    assert steady.heard == [1]


def test_raising_subscription_callback_is_supervised() -> None:
    rt = Runtime()
    picky = Worker("picky", fail_on=13)
    rt.add(picky)
    other = Worker("other")
    rt.add(other)
    rt.start()
    rt.bus.publish("cmd", Num(13))
    rt.spin_for(0.5)

    health = rt.supervisor.health["picky"]
    assert (health.failures, health.restarts, health.failed_permanently) == (1, 1, False)
    assert health.last_error == "ValueError: cannot handle 13"
    assert picky.running and picky.starts == 2
    assert other.heard == [13]

    rt.bus.publish("cmd", Num(2))
    rt.spin_for(0.5)
    assert picky.heard == [13, 2]  # once each: the old subscription is gone
    assert other.heard == [13, 2]


def test_failed_restart_is_permanent_and_releases_partial_start() -> None:
    class BadRestart(Worker):
        def on_start(self) -> None:
            self.starts += 1
            self.create_timer(1.0, self.tick)
            if self.starts > 1:
                raise RuntimeError("cannot come back")

    rt = Runtime()
    node = BadRestart("bad", fail_at={1.0})
    rt.add(node)
    rt.start()
    rt.spin_for(5.0)

    health = rt.supervisor.health["bad"]
    assert health.failed_permanently
    assert health.failures == 1
    assert not node.running
    assert node.starts == 2
    assert node.ticks == [1.0]  # the timer of the failed start does not keep firing


def test_failing_on_start_is_supervised() -> None:
    class BadStart(Node):
        def __init__(self) -> None:
            super().__init__("bad-start")
            self.starts = 0

        def on_start(self) -> None:
            self.starts += 1
            raise RuntimeError("no device")

    rt = Runtime(max_restarts=3)
    node = BadStart()
    rt.add(node)
    rt.start()  # must not raise
    assert rt.supervisor.health["bad-start"] == NodeHealth(
        failures=1, restarts=1, failed_permanently=True, last_error="RuntimeError: no device"
    )
    assert node.starts == 2
    assert not node.running


def test_failure_outside_a_node_is_logged_only(caplog: pytest.LogCaptureFixture) -> None:
    rt = Runtime()
    ticks = 0

    def tick() -> None:
        nonlocal ticks
        ticks += 1
        raise RuntimeError("ownerless")

    rt.create_timer(1.0, tick)
    with caplog.at_level(logging.ERROR, logger="amiro.runtime"):
        rt.spin_for(3.0)
    assert ticks == 3
    assert rt.supervisor.health == {}
    assert sum("outside any node" in r.getMessage() for r in caplog.records) == 3
