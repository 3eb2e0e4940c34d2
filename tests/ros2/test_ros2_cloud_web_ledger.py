"""The cloud's ledger re-sends what was raised before the edge listened: in the web
deployment the cloud builds the dashboard and dialogue while the simulator's time already
runs, and a notification raised before the edge's first heartbeat would otherwise be lost."""

from __future__ import annotations

from amiro.core import names
from amiro.core.clock import SimClock
from amiro.core.messages import Acknowledgement, BehaviorEvent, Notification
from amiro.core.runtime import Runtime
from amiro.deploy.health import NotificationLedger


def test_notifications_raised_before_the_edge_is_up_are_sent_again() -> None:
    runtime = Runtime(SimClock())
    ledger = runtime.add(NotificationLedger(resend_delay_s=0.5))
    sent: list[Notification] = []
    runtime.bus.subscribe(names.NOTIFICATIONS, Notification, sent.append, depth=10)
    runtime.start()
    note = Notification("hot-1", "maria", "hydration", 5)
    runtime.bus.publish(names.NOTIFICATIONS, note)
    runtime.spin_for(0.1)
    runtime.bus.publish(names.EVENTS, BehaviorEvent(0.2, "node_up", detail={"node": "sim"}))
    runtime.spin_for(1.0)
    assert [n.id for n in sent] == ["hot-1"]  # another process coming up changes nothing
    runtime.bus.publish(names.EVENTS, BehaviorEvent(1.2, "node_up", detail={"node": "edge"}))
    runtime.spin_for(1.0)
    assert [n.id for n in sent] == ["hot-1", "hot-1"] and ledger.resent == 1
    runtime.bus.publish(names.ACK, Acknowledgement("hot-1", "done", "t"))
    runtime.bus.publish(names.EVENTS, BehaviorEvent(2.5, "node_up", detail={"node": "edge"}))
    runtime.spin_for(1.0)
    assert len(sent) == 2 and ledger.pending == {}
