"""The executor (timers, spinning, determinism) and the simulated clock."""

from __future__ import annotations

import time
from dataclasses import dataclass

import pytest

from amiro.core.clock import SimClock
from amiro.core.runtime import Runtime


@dataclass(frozen=True)
class Num:
    value: int


def test_timers_fire_in_due_order() -> None:
    rt = Runtime()
    fired: list[tuple[str, float]] = []

    def mark(name: str) -> None:
        fired.append((name, rt.clock.now()))

    rt.call_later(3.0, lambda: mark("c"))
    rt.call_later(1.0, lambda: mark("a"))
    rt.call_later(2.0, lambda: mark("b"))
    rt.call_later(0.5, lambda: mark("first"))
    rt.spin_for(5.0)
    assert fired == [("first", 0.5), ("a", 1.0), ("b", 2.0), ("c", 3.0)]


def test_ties_break_in_creation_order() -> None:
    rt = Runtime()
    fired: list[str] = []
    for name in ("z", "m", "a"):
        rt.call_later(1.0, lambda n=name: fired.append(n))  # type: ignore[misc]
    rt.spin_for(1.0)
    assert fired == ["z", "m", "a"]


def test_periodic_timer_keeps_creation_order_on_ties() -> None:
    rt = Runtime()
    fired: list[tuple[str, float]] = []
    rt.create_timer(1.0, lambda: fired.append(("fast", rt.clock.now())))
    rt.create_timer(2.0, lambda: fired.append(("slow", rt.clock.now())))
    rt.call_later(2.0, lambda: fired.append(("once", rt.clock.now())))
    rt.spin_for(4.0)
    assert fired == [
        ("fast", 1.0),
        ("fast", 2.0),
        ("slow", 2.0),
        ("once", 2.0),
        ("fast", 3.0),
        ("fast", 4.0),
        ("slow", 4.0),
    ]


def test_periodic_timer_and_cancel() -> None:
    rt = Runtime()
    times: list[float] = []
    timer = rt.create_timer(0.25, lambda: times.append(rt.clock.now()))
    rt.spin_for(1.0)
    assert times == [0.25, 0.5, 0.75, 1.0]
    timer.cancel()
    rt.spin_for(1.0)
    assert times == [0.25, 0.5, 0.75, 1.0]


def test_timer_cancelled_from_its_own_callback() -> None:
    rt = Runtime()
    count = 0

    def tick() -> None:
        nonlocal count
        count += 1
        if count == 3:
            timer.cancel()

    timer = rt.create_timer(0.5, tick)
    rt.spin_for(10.0)
    assert count == 3


def test_timer_period_must_be_positive() -> None:
    rt = Runtime()
    with pytest.raises(ValueError, match="positive"):
        rt.create_timer(0.0, lambda: None)
    with pytest.raises(ValueError):
        rt.create_timer(-1.0, lambda: None)


def test_call_later_fires_once_at_its_time() -> None:
    rt = Runtime()
    rt.spin_for(1.0)
    times: list[float] = []
    rt.call_later(0.5, lambda: times.append(rt.clock.now()))
    rt.call_later(-3.0, lambda: times.append(rt.clock.now()))  # never in the past
    cancelled = rt.call_later(0.25, lambda: times.append(-1.0))
    cancelled.cancel()
    rt.spin_for(5.0)
    assert times == [1.0, 1.5]


def test_spin_for_advances_clock_exactly() -> None:
    rt = Runtime()
    rt.spin_for(2.5)  # no timers at all
    assert rt.clock.now() == 2.5
    fired: list[float] = []
    rt.call_later(0.5, lambda: fired.append(rt.clock.now()))  # due at 3.0
    rt.create_timer(0.3, lambda: None)
    rt.spin_for(0.25)
    assert rt.clock.now() == 2.75
    assert fired == []
    rt.spin_for(0.25)
    assert rt.clock.now() == 3.0
    assert fired == [3.0]  # a timer due exactly at the end fires


def test_spin_delivers_messages_published_by_timers() -> None:
    rt = Runtime()
    got: list[tuple[int, float]] = []
    rt.bus.subscribe("n", Num, lambda m: got.append((m.value, rt.clock.now())))
    pub = rt.bus.publisher("n", Num)
    counter = iter(range(100))
    rt.create_timer(1.0, lambda: pub.publish(Num(next(counter))))
    pub.publish(Num(-1))  # published outside any callback
    rt.spin_for(3.0)
    assert got == [(-1, 0.0), (0, 1.0), (1, 2.0), (2, 3.0)]


def test_spin_until_stops_when_predicate_holds() -> None:
    rt = Runtime()
    ticks = 0

    def tick() -> None:
        nonlocal ticks
        ticks += 1

    rt.create_timer(0.5, tick)
    assert rt.spin_until(lambda: ticks >= 3, timeout=10.0)
    assert ticks == 3
    assert rt.clock.now() == 1.5


def test_spin_until_already_true_does_not_advance() -> None:
    rt = Runtime()
    rt.create_timer(0.5, lambda: None)
    assert rt.spin_until(lambda: True, timeout=10.0)
    assert rt.clock.now() == 0.0


def test_spin_until_times_out_at_deadline() -> None:
    rt = Runtime()
    ticks = 0

    def tick() -> None:
        nonlocal ticks
        ticks += 1

    rt.create_timer(0.75, tick)
    rt.spin_for(1.0)
    assert not rt.spin_until(lambda: ticks >= 100, timeout=2.0)
    assert rt.clock.now() == 3.0
    assert ticks == 4  # 0.75, 1.5, 2.25, 3.0

    idle = Runtime()
    assert not idle.spin_until(lambda: False, timeout=4.0)
    assert idle.clock.now() == 4.0


def _trace(seed: int) -> list[tuple[float, float, int]]:
    rt = Runtime(seed=seed)
    out: list[tuple[float, float, int]] = []

    def sample() -> None:
        out.append((rt.clock.now(), float(rt.rng.normal()), rt.random.randint(0, 10**9)))
        rt.call_later(float(rt.rng.uniform(0.0, 0.5)), lambda: out.append((rt.clock.now(), 0, 0)))

    rt.create_timer(0.1, sample)
    rt.spin_for(5.0)
    return out


def test_same_seed_same_run() -> None:
    a = Runtime(seed=42)
    b = Runtime(seed=42)
    assert a.rng.random(8).tolist() == b.rng.random(8).tolist()
    assert [a.random.random() for _ in range(8)] == [b.random.random() for _ in range(8)]

    run = _trace(7)
    assert len(run) > 50
    assert run == _trace(7)
    assert run != _trace(8)


def test_fast_clock_never_sleeps(monkeypatch: pytest.MonkeyPatch) -> None:
    def no_sleep(seconds: float) -> None:
        raise AssertionError(f"slept {seconds}")

    monkeypatch.setattr(time, "sleep", no_sleep)
    rt = Runtime(clock=SimClock())
    count = 0

    def tick() -> None:
        nonlocal count
        count += 1

    rt.create_timer(1.0, tick)
    rt.spin_for(3600.0)
    assert count == 3600
    assert rt.clock.now() == 3600.0


def test_paced_clock_follows_wall_time() -> None:
    rt = Runtime(clock=SimClock(speed=10.0))
    rt.create_timer(0.25, lambda: None)
    start = time.perf_counter()
    rt.spin_for(1.0)
    elapsed = time.perf_counter() - start
    assert rt.clock.now() == 1.0
    assert 0.05 <= elapsed <= 0.5


def test_invalid_speed_raises() -> None:
    for bad in (0.0, -2.0):
        with pytest.raises(ValueError, match="positive"):
            SimClock(speed=bad)
    clock = SimClock()
    with pytest.raises(ValueError):
        clock.set_speed(0.0)
    assert clock.speed is None


def test_sim_clock_start_and_no_going_back() -> None:
    clock = SimClock(start=10.0)
    assert clock.now() == 10.0
    clock.advance_to(12.5)
    assert clock.now() == 12.5
    clock.advance_to(11.0)
    assert clock.now() == 12.5
