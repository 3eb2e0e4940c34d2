"""The cloud's notification ledger on disk: what a restarted cloud finds and re-sends."""

from __future__ import annotations

import json
from pathlib import Path

from amiro.core import names
from amiro.core.clock import SimClock
from amiro.core.messages import Acknowledgement, BehaviorEvent, Notification
from amiro.core.runtime import Runtime
from amiro.deploy.config import NodeConfig
from amiro.deploy.health import NotificationLedger
from amiro.deploy.ledger_store import LedgerFile, LedgerStore

NOTE = Notification("hot-1", "maria", "hydration", 5, "28 C in the living room")
CHECKPOINT = {"run": "r1", "graph": "hydration", "task": "offer_water", "finished": []}


def _cloud(path: Path) -> tuple[Runtime, NotificationLedger, list[Notification]]:
    runtime = Runtime(SimClock())
    ledger = runtime.add(NotificationLedger(resend_delay_s=0.5, store=LedgerStore(path)))
    sent: list[Notification] = []
    runtime.bus.subscribe(names.NOTIFICATIONS, Notification, sent.append, depth=10)
    runtime.start()
    return runtime, ledger, sent


def _checkpoint_event(ident: str) -> BehaviorEvent:
    detail = {"id": ident, "checkpoint": CHECKPOINT}
    return BehaviorEvent(0.5, "behavior_checkpoint", detail=detail)


def test_a_restarted_cloud_resends_the_pending_notification_with_its_checkpoint(
    tmp_path: Path,
) -> None:
    path = tmp_path / "ledger.json"
    runtime, _, _ = _cloud(path)
    runtime.bus.publish(names.NOTIFICATIONS, NOTE)
    runtime.spin_for(0.1)
    runtime.bus.publish(names.EVENTS, _checkpoint_event("hot-1"))
    runtime.spin_for(0.1)
    runtime.stop()  # the file is all that is left of the first cloud

    runtime, ledger, sent = _cloud(path)
    assert ledger.restored == 1 and ledger.checkpoints == {"hot-1": CHECKPOINT}
    runtime.bus.publish(names.EVENTS, BehaviorEvent(1.0, "node_up", detail={"node": "edge"}))
    runtime.spin_for(1.0)
    assert [n.id for n in sent] == ["hot-1"]
    assert sent[0].checkpoint == CHECKPOINT and sent[0].reason == NOTE.reason
    assert ledger.persistence()["ledger"]["restored"] == 1


def test_an_acknowledgement_removes_the_entry_from_the_file(tmp_path: Path) -> None:
    path = tmp_path / "ledger.json"
    runtime, ledger, _ = _cloud(path)
    other = Notification("hot-2", "ahmed", "hydration", 5)
    for note in (NOTE, other):
        runtime.bus.publish(names.NOTIFICATIONS, note)
    runtime.bus.publish(names.EVENTS, _checkpoint_event("hot-1"))
    runtime.spin_for(0.1)
    assert set(json.loads(path.read_text())["pending"]) == {"hot-1", "hot-2"}
    runtime.bus.publish(names.ACK, Acknowledgement("hot-1", "done", "t"))
    runtime.spin_for(0.1)
    saved = LedgerStore(path).load()
    assert list(saved.pending) == ["hot-2"] and saved.checkpoints == {}
    assert not (tmp_path / "ledger.json.tmp").exists()  # replaced, not left behind
    assert list(ledger.pending) == ["hot-2"]


def test_a_corrupt_file_is_moved_aside_and_the_ledger_starts_empty(tmp_path: Path) -> None:
    path = tmp_path / "ledger.json"
    path.write_text('{"version": 1, "pending": {"hot-1": {"id": "hot-1"', encoding="utf-8")
    runtime, ledger, _ = _cloud(path)
    assert ledger.pending == {} and ledger.restored == 0
    report = ledger.persistence()["ledger"]
    assert report["corrupt"] == 1
    assert (tmp_path / "ledger.json.corrupt").read_text().startswith('{"version": 1')
    runtime.bus.publish(names.NOTIFICATIONS, NOTE)  # and it keeps working
    runtime.spin_for(0.1)
    assert list(LedgerStore(path).load().pending) == ["hot-1"]


def test_unusable_files_start_empty_without_raising(tmp_path: Path) -> None:
    wrong_version = tmp_path / "v9.json"
    wrong_version.write_text(LedgerFile(version=9).model_dump_json(), encoding="utf-8")
    binary = tmp_path / "binary.json"
    binary.write_bytes(b"\xff\xfe\x00garbage")
    for path in (wrong_version, binary):
        store = LedgerStore(path)
        assert store.load() == LedgerFile() and store.corrupt == 1
        assert not path.exists()


def test_a_failed_write_is_counted_not_raised(tmp_path: Path) -> None:
    (tmp_path / "blocker").write_text("a file where the directory should be")
    store = LedgerStore(tmp_path / "blocker" / "ledger.json")
    store.save(LedgerFile(pending={"hot-1": NOTE}))
    assert store.write_errors == 1


def test_a_relative_ledger_path_is_taken_from_the_log_dir(tmp_path: Path) -> None:
    node = NodeConfig(role="cloud", ledger_path=Path("ledger.json"))
    assert node.with_ledger_base(tmp_path).ledger_path == tmp_path / "ledger.json"
    absolute = NodeConfig(role="cloud", ledger_path=tmp_path / "elsewhere.json")
    assert absolute.with_ledger_base(Path("/logs")).ledger_path == tmp_path / "elsewhere.json"
    assert NodeConfig(role="cloud").with_ledger_base(tmp_path).ledger_path is None
