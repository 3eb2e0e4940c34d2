"""The checkpoint's JSON form: a round trip for what tasks share, clear errors for the rest."""

from __future__ import annotations

import json
from typing import Any

import pytest

from amiro.behavior.checkpoint import (
    Checkpoint,
    CheckpointError,
    FinishedTask,
    decode_value,
    encode_value,
    portable,
)
from amiro.core.messages import Point, Pose2D


def wire() -> dict[str, Any]:
    return Checkpoint(
        run="hydration#1",
        graph="hydration",
        task="approach",
        finished=(FinishedTask("search", "success"),),
        blackboard={"notification_id": "n1", "person_position": Point(1.0, 2.0, 0.9)},
        stamp=12.5,
    ).to_dict()


def test_round_trip_through_json_keeps_messages_and_structure() -> None:
    value = {"route": [Pose2D(1.0, 2.0, 0.5), "kitchen"], "n": 2, "ok": True, "none": None}
    assert decode_value(json.loads(json.dumps(encode_value(value)))) == {
        "route": [Pose2D(1.0, 2.0, 0.5), "kitchen"],
        "n": 2,
        "ok": True,
        "none": None,
    }
    assert encode_value((1, 2)) == [1, 2]  # JSON has no tuples
    checkpoint = Checkpoint.from_dict(json.loads(json.dumps(wire())))
    assert checkpoint.notification_id == "n1"
    assert checkpoint.blackboard["person_position"] == Point(1.0, 2.0, 0.9)
    assert checkpoint.to_dict() == wire()


def test_unencodable_values_are_left_out_by_key() -> None:
    kept, omitted = portable({"a": Point(), "f": len, "tagged": {"$msg": "Point"}})
    assert kept == {"a": Point()} and omitted == ("f", "tagged")


@pytest.mark.parametrize(
    ("mangle", "message"),
    [
        (lambda d: "not json", "not a JSON object"),
        (lambda d: {k: v for k, v in d.items() if k != "task"}, "task: Field required"),
        (lambda d: {**d, "task": ""}, "task: String should have at least 1 character"),
        (lambda d: {**d, "stamp": float("nan")}, "stamp: Input should be a finite number"),
        (lambda d: {**d, "stamp": "12"}, "stamp: Input should be a valid number"),
        (lambda d: {**d, "finished": [{"task": "search", "result": "preempted"}]}, "result"),
        (lambda d: {**d, "finished": "search"}, "finished: Input should be a valid list"),
        (lambda d: {**d, "surprise": 1}, "surprise: Extra inputs are not permitted"),
        (lambda d: {**d, "blackboard": {"p": {"$msg": "Nope"}}}, "unknown message type 'Nope'"),
        (lambda d: {**d, "blackboard": {"p": {"$msg": "Point", "fields": "x"}}}, "not a Point"),
    ],
)
def test_malformed_checkpoints_are_refused_with_the_reason(mangle: Any, message: str) -> None:
    with pytest.raises(CheckpointError, match="bad checkpoint") as caught:
        Checkpoint.from_dict(mangle(wire()))
    assert message in str(caught.value)
