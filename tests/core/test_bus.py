"""The bus: topics (queues, ordering, errors), services and actions."""

from __future__ import annotations

import logging
from dataclasses import dataclass

import pytest

from amiro.core.bus import ActionServer, Bus, BusError, GoalHandle, GoalStatus
from amiro.core.messages import String


@dataclass(frozen=True)
class Num:
    value: int


# --- topics ------------------------------------------------------------------------------


def test_messages_wait_for_spin_and_arrive_in_order() -> None:
    bus = Bus()
    first: list[int] = []
    second: list[int] = []
    bus.subscribe("n", Num, lambda m: first.append(m.value))
    bus.subscribe("n", Num, lambda m: second.append(m.value))
    pub = bus.publisher("n", Num)
    for i in range(5):
        pub.publish(Num(i))

    assert first == [] and second == []
    assert bus.pending()
    assert bus.spin_some() == 10
    assert first == [0, 1, 2, 3, 4]
    assert second == [0, 1, 2, 3, 4]
    assert not bus.pending()
    assert bus.spin_some() == 0
    stats = bus.stats("n")
    assert (stats.published, stats.delivered, stats.dropped, stats.rejected) == (5, 10, 0, 0)
    assert bus.topics() == {"n": "Num"}


def test_full_queue_drops_oldest_and_counts() -> None:
    bus = Bus()
    slow: list[int] = []
    roomy: list[int] = []
    slow_sub = bus.subscribe("n", Num, lambda m: slow.append(m.value), depth=3)
    roomy_sub = bus.subscribe("n", Num, lambda m: roomy.append(m.value), depth=10)
    for i in range(7):
        bus.publish("n", Num(i))

    assert slow_sub.dropped == 4
    assert roomy_sub.dropped == 0
    assert bus.stats("n").dropped == 4
    bus.spin_some()
    assert slow == [4, 5, 6]
    assert roomy == list(range(7))
    assert bus.stats("n").delivered == 3 + 7


def test_depth_below_one_is_refused() -> None:
    with pytest.raises(BusError, match="depth"):
        Bus().subscribe("n", Num, lambda m: None, depth=0)


def test_type_mismatch_raises_and_counts_rejected() -> None:
    bus = Bus()
    got: list[object] = []
    bus.subscribe("n", Num, got.append)
    pub = bus.publisher("n", Num)

    with pytest.raises(BusError, match="n carries Num, got String"):
        bus.publish("n", String("nope"))
    with pytest.raises(BusError):
        pub.publish(String("nope"))  # type: ignore[arg-type]
    stats = bus.stats("n")
    assert stats.rejected == 2
    assert stats.published == 0
    bus.spin_some()
    assert got == []

    with pytest.raises(BusError):
        bus.subscribe("n", String, lambda m: None)
    with pytest.raises(BusError):
        bus.publisher("n", String)
    # the topic still works with its own type
    bus.publish("n", Num(1))
    bus.spin_some()
    assert got == [Num(1)]


def test_first_publish_fixes_the_topic_type() -> None:
    bus = Bus()
    bus.publish("fresh", Num(1))
    with pytest.raises(BusError):
        bus.publish("fresh", String("x"))
    assert bus.stats("fresh").rejected == 1


def test_publishing_callback_does_not_reenter() -> None:
    bus = Bus()
    trace: list[str] = []

    def on_a(m: Num) -> None:
        trace.append(f"a{m.value}-start")
        bus.publish("b", Num(m.value))
        trace.append(f"a{m.value}-end")

    bus.subscribe("a", Num, on_a)
    bus.subscribe("b", Num, lambda m: trace.append(f"b{m.value}"))
    bus.publish("a", Num(1))
    bus.publish("a", Num(2))

    assert bus.spin_some() == 4  # everything, on the same spin
    assert trace == ["a1-start", "a1-end", "a2-start", "a2-end", "b1", "b2"]


def test_callback_publishing_on_its_own_topic_runs_after_it_returns() -> None:
    bus = Bus()
    trace: list[str] = []
    depth = 0

    def on_n(m: Num) -> None:
        nonlocal depth
        depth += 1
        assert depth == 1, "re-entered"
        trace.append(f"start{m.value}")
        if m.value < 3:
            bus.publish("n", Num(m.value + 1))
        trace.append(f"end{m.value}")
        depth -= 1

    bus.subscribe("n", Num, on_n)
    bus.publish("n", Num(0))
    assert bus.spin_some() == 4
    assert trace == [f"{edge}{i}" for i in range(4) for edge in ("start", "end")]


def test_raising_callback_goes_to_on_error_and_others_still_get_the_message() -> None:
    errors: list[tuple[object | None, BaseException]] = []
    bus = Bus(on_error=lambda owner, exc: errors.append((owner, exc)))
    owner = object()
    flaky: list[int] = []
    good: list[int] = []

    def boom(m: Num) -> None:
        flaky.append(m.value)
        if m.value == 1:
            raise ValueError("bad message")

    bus.subscribe("n", Num, boom, owner=owner)
    bus.subscribe("n", Num, lambda m: good.append(m.value))
    for i in range(3):
        bus.publish("n", Num(i))

    assert bus.spin_some() == 6
    assert good == [0, 1, 2]
    assert flaky == [0, 1, 2]  # the failing subscriber keeps receiving later messages
    assert len(errors) == 1
    assert errors[0][0] is owner
    assert isinstance(errors[0][1], ValueError)


def test_default_error_hook_logs(caplog: pytest.LogCaptureFixture) -> None:
    bus = Bus()

    def boom(m: Num) -> None:
        raise ValueError("kaput")

    bus.subscribe("n", Num, boom, owner="someone")
    bus.publish("n", Num(0))
    with caplog.at_level(logging.ERROR, logger="amiro.bus"):
        bus.spin_some()
    assert any("someone" in r.getMessage() and "kaput" in r.getMessage() for r in caplog.records)


def test_destroyed_subscription_gets_nothing() -> None:
    bus = Bus()
    got: list[int] = []
    sub = bus.subscribe("n", Num, lambda m: got.append(m.value))
    bus.publish("n", Num(1))  # queued before destroy: discarded
    sub.destroy()
    bus.publish("n", Num(2))
    bus.spin_some()
    assert got == []
    assert not sub.active
    assert bus.stats("n").delivered == 0


def test_subscription_destroyed_during_spin_gets_nothing_more() -> None:
    bus = Bus()
    got: list[int] = []
    victim = None

    def killer(m: Num) -> None:
        assert victim is not None
        victim.destroy()

    bus.subscribe("n", Num, killer)
    victim = bus.subscribe("n", Num, lambda m: got.append(m.value))
    bus.publish("n", Num(1))
    bus.publish("n", Num(2))
    bus.spin_some()
    assert got == []


# --- services ----------------------------------------------------------------------------


def test_service_call_returns_handler_result() -> None:
    bus = Bus()

    def add(req: tuple[int, int]) -> int:
        return req[0] + req[1]

    bus.create_service("add", add)
    assert bus.has_service("add")
    assert bus.call("add", (2, 3)) == 5
    assert bus.call("add", (10, -4)) == 6


def test_unknown_service_raises() -> None:
    bus = Bus()
    with pytest.raises(BusError, match="no service named ghost"):
        bus.call("ghost", None)
    bus.create_service("gone", lambda req: req)
    bus.remove_service("gone")
    with pytest.raises(BusError):
        bus.call("gone", None)


def test_duplicate_service_raises_and_keeps_the_first() -> None:
    bus = Bus()
    bus.create_service("svc", lambda req: "first")
    with pytest.raises(BusError, match="already"):
        bus.create_service("svc", lambda req: "second")
    assert bus.call("svc", None) == "first"


# --- actions -----------------------------------------------------------------------------


class Countdown(ActionServer[int, int, str]):
    """Accepts positive goals; the test drives the handles by hand."""

    def __init__(self) -> None:
        self.handles: list[GoalHandle[int, int, str]] = []
        self.cancels: list[GoalHandle[int, int, str]] = []

    def accept(self, goal: int) -> bool:
        return goal > 0

    def execute(self, handle: GoalHandle[int, int, str]) -> None:
        self.handles.append(handle)

    def cancel(self, handle: GoalHandle[int, int, str]) -> None:
        self.cancels.append(handle)
        super().cancel(handle)

    def canceled_result(self, handle: GoalHandle[int, int, str]) -> str:
        return f"canceled at {handle.feedback}"


@pytest.fixture
def action_bus() -> tuple[Bus, Countdown]:
    bus = Bus()
    server = Countdown()
    bus.create_action_server("count", server)
    return bus, server


def test_goal_accepted_and_executing(action_bus: tuple[Bus, Countdown]) -> None:
    bus, server = action_bus
    handle = bus.send_goal("count", 3)
    assert handle.status is GoalStatus.EXECUTING
    assert not handle.done
    assert handle.goal == 3
    assert server.handles == [handle]


def test_goal_rejected(action_bus: tuple[Bus, Countdown]) -> None:
    bus, server = action_bus
    handle = bus.send_goal("count", -1)
    assert handle.status is GoalStatus.REJECTED
    assert handle.done
    assert server.handles == []
    seen: list[GoalStatus] = []
    handle.on_done(lambda h: seen.append(h.status))
    assert seen == [GoalStatus.REJECTED]
    handle.cancel()  # nothing to cancel
    assert server.cancels == []


def test_feedback_reaches_callbacks(action_bus: tuple[Bus, Countdown]) -> None:
    bus, server = action_bus
    handle = bus.send_goal("count", 3)
    a: list[int] = []
    b: list[int] = []
    handle.on_feedback(a.append)
    handle.on_feedback(b.append)
    server.handles[0].publish_feedback(2)
    server.handles[0].publish_feedback(1)
    assert a == [2, 1]
    assert b == [2, 1]
    assert handle.feedback == 1


def test_succeed_fires_done_once(action_bus: tuple[Bus, Countdown]) -> None:
    bus, server = action_bus
    handle = bus.send_goal("count", 3)
    calls: list[tuple[GoalStatus, str | None]] = []
    handle.on_done(lambda h: calls.append((h.status, h.result)))
    server.handles[0].succeed("lift-off")
    server.handles[0].succeed("again")
    server.handles[0].abort("too late")
    handle.cancel()
    assert calls == [(GoalStatus.SUCCEEDED, "lift-off")]
    assert handle.status is GoalStatus.SUCCEEDED
    assert handle.result == "lift-off"
    assert server.cancels == []


def test_abort_result(action_bus: tuple[Bus, Countdown]) -> None:
    bus, server = action_bus
    handle = bus.send_goal("count", 3)
    calls: list[GoalStatus] = []
    handle.on_done(lambda h: calls.append(h.status))
    server.handles[0].abort("stuck")
    assert calls == [GoalStatus.ABORTED]
    assert handle.result == "stuck"
    assert handle.done


def test_cancel_calls_server_and_ends_canceled(action_bus: tuple[Bus, Countdown]) -> None:
    bus, server = action_bus
    handle = bus.send_goal("count", 3)
    server.handles[0].publish_feedback(2)
    calls: list[GoalStatus] = []
    handle.on_done(lambda h: calls.append(h.status))
    handle.cancel()
    handle.cancel()
    assert server.cancels == [handle]
    assert handle.cancel_requested
    assert handle.status is GoalStatus.CANCELED
    assert handle.result == "canceled at 2"
    assert calls == [GoalStatus.CANCELED]


def test_server_may_wind_down_before_canceling() -> None:
    class Slow(Countdown):
        def cancel(self, handle: GoalHandle[int, int, str]) -> None:
            self.cancels.append(handle)  # finishes later

    bus = Bus()
    server = Slow()
    bus.create_action_server("slow", server)
    handle = bus.send_goal("slow", 1)
    handle.cancel()
    assert handle.cancel_requested
    assert handle.status is GoalStatus.EXECUTING
    server.handles[0].canceled("stopped")
    assert server.handles[0].status is GoalStatus.CANCELED
    assert handle.result == "stopped"


def test_on_done_after_completion_fires_immediately(action_bus: tuple[Bus, Countdown]) -> None:
    bus, server = action_bus
    handle = bus.send_goal("count", 3)
    server.handles[0].succeed("ok")
    seen: list[str | None] = []
    handle.on_done(lambda h: seen.append(h.result))
    assert seen == ["ok"]


def test_unknown_and_duplicate_actions(action_bus: tuple[Bus, Countdown]) -> None:
    bus, _ = action_bus
    with pytest.raises(BusError, match="no action server named ghost"):
        bus.send_goal("ghost", 1)
    with pytest.raises(BusError, match="already"):
        bus.create_action_server("count", Countdown())
    assert bus.has_action("count")
    bus.remove_action_server("count")
    assert not bus.has_action("count")
