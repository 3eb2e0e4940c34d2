"""Reminders (daily, conditional, calendar) and the notification ledger across a restart."""

from __future__ import annotations

from pathlib import Path

import pytest

from amiro.core import names
from amiro.core.config import ConfigError, parse
from amiro.core.messages import Acknowledgement, Notification, SensorReading
from amiro.core.runtime import Runtime
from amiro.environment.ledger import LedgerNode, NotificationLedger
from amiro.environment.reminders import RemindersConfig, RemindersNode

# The simulated clock starts on 2026-07-15 at 10:00 UTC.
CONFIG = {
    "timezone": "UTC",
    "reminders": [
        {
            "name": "medication",
            "kind": "medication",
            "user": "maria",
            "daily_at": "08:00",
            "priority": 8,
        },
        {
            "name": "drink",
            "kind": "hydration",
            "every_s": 7200,
            "while": {"room": "living_room", "above": 28},
        },
    ],
    "calendar": [
        {"title": "doctor", "at": "2026-07-15T15:00:00", "user": "maria", "remind_before_s": 1800}
    ],
}


def reading(rt: Runtime, value: float) -> None:
    rt.bus.publish(
        names.SENSORS,
        SensorReading("home", "living_room", "temperature", value, "C", rt.clock.now()),
    )


def test_daily_conditional_and_calendar_reminders() -> None:
    rt = Runtime()
    rt.add(RemindersNode(parse(RemindersConfig, CONFIG, "reminders")))
    notes: list[tuple[float, Notification]] = []
    rt.bus.subscribe(
        names.NOTIFICATIONS, Notification, lambda n: notes.append((rt.clock.now(), n)), 100
    )
    rt.start()
    reading(rt, 25.0)
    rt.spin_for(3600.0)
    assert notes == []  # cool room, no appointment yet, medication is tomorrow
    reading(rt, 30.0)  # 11:00, hot: hydration now, then every two hours while hot
    rt.spin_for(5 * 3600.0)  # to 16:00
    reading(rt, 26.0)  # cooled down: no more hydration reminders
    rt.spin_for(17 * 3600.0)  # to 09:00 next day
    kinds = [(round(t / 3600, 2), n.kind) for t, n in notes]
    assert kinds == [
        (1.0, "hydration"),
        (3.0, "hydration"),
        (4.5, "calendar"),  # 14:30, half an hour before the doctor
        (5.0, "hydration"),
        (22.0, "medication"),  # 08:00 the next day
    ]
    med = notes[-1][1]
    assert (med.user, med.priority, med.id) == ("maria", 8, "medication-20260716T080000")


def test_reminder_config_errors_are_one_line() -> None:
    with pytest.raises(ConfigError, match="exactly one of daily_at, every_s"):
        parse(RemindersConfig, {"reminders": [{"name": "x", "kind": "k"}]}, "r")
    with pytest.raises(ConfigError, match="unknown time zone"):
        parse(RemindersConfig, {"timezone": "Mars/Olympus"}, "r")


def test_pending_notifications_survive_a_restart_and_acks_are_stored(tmp_path: Path) -> None:
    url = f"sqlite:///{tmp_path / 'ledger.db'}"
    rt = Runtime()
    rt.add(LedgerNode(NotificationLedger(url)))
    rt.start()
    for i in range(3):
        rt.bus.publish(names.NOTIFICATIONS, Notification(f"n{i}", "maria", "hydration", i))
    rt.spin_for(1.0)
    rt.bus.publish(names.ACK, Acknowledgement("n1", "done", "2026-07-15T10:00:01+00:00"))
    rt.spin_for(1.0)
    rt.stop()  # the process ends with n0 and n2 unanswered

    rt2 = Runtime()
    ledger = NotificationLedger(url)
    rt2.add(LedgerNode(ledger))
    replayed: list[Notification] = []
    rt2.bus.subscribe(names.NOTIFICATIONS, Notification, replayed.append, 100)
    rt2.start()
    rt2.spin_for(1.0)
    assert sorted(n.id for n in replayed) == ["n0", "n2"]
    assert {n["id"]: n["status"] for n in ledger.recent()} == {
        "n0": "pending",
        "n1": "done",
        "n2": "pending",
    }
    assert ledger.ack_count() == 1
    rt2.supervisor.report(rt2.nodes["notification_ledger"], RuntimeError("boom"))  # restart
    rt2.spin_for(1.0)
    assert len(replayed) == 2  # replayed once per process, not on every node restart
