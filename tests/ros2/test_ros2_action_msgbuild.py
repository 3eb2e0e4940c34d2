"""Action types from ``.action`` files: the builder expands them as ament does (Goal, Result,
Feedback, SendGoal, GetResult, FeedbackMessage) with upstream's type hashes, and the
packages setup builds (nav2_msgs, hri_msgs, amiro_interfaces) are the upstream types."""

from __future__ import annotations

import json
import shutil
import sys
from pathlib import Path

import pytest

from amiro.ros2.msgbuild import build_package
from amiro.ros2.msgbuild.package import load_package

SHARE = Path(sys.prefix) / "share"
# Upstream Jazzy's test_msgs wheel (PyPI) ships Fibonacci.action with its type description.
UPSTREAM_FIBONACCI = SHARE / "test_msgs" / "action"
# nav2_msgs 1.3.x (Jazzy), NavigateToPose_FeedbackMessage, the type of the topic
# /navigate_to_pose/_action/feedback: the hash a third-party decoder of Nav2 Jazzy
# recordings pins for it (it carries the Feedback and the goal id, so it checks every
# feedback field; the goal and result are checked through the SendGoal/GetResult names).
JAZZY_NAV2_FEEDBACK_HASH = "RIHS01_9d1f6fa2eb975ce733b419ac2e97b134d8ff92b6478b6559feed9a50bdfd82b3"
# What `ros2 interface show hri_msgs/msg/IdsList` gives on Jazzy: std_msgs/Header + string[].
EXPANDED = (
    "Goal",
    "Result",
    "Feedback",
    "FeedbackMessage",
    "SendGoal_Request",
    "SendGoal_Response",
    "GetResult_Request",
    "GetResult_Response",
)


def _hashes(description: Path) -> dict[str, str]:
    data = json.loads(description.read_text("utf-8"))
    return {h["type_name"]: h["hash_string"] for h in data["type_hashes"]}


def test_an_action_builds_with_upstreams_hashes(tmp_path: Path) -> None:
    """Fibonacci.action from upstream's own package, built here: all 16 hashes (the action,
    its messages, services and service events) equal the ones upstream shipped."""
    source = tmp_path / "interfaces" / "test_msgs" / "action"
    source.mkdir(parents=True)
    shutil.copy(UPSTREAM_FIBONACCI / "Fibonacci.action", source)
    package = load_package("test_msgs", tmp_path / "interfaces")
    assert package.kinds == ("action",)
    assert set(package.dependencies) >= {"action_msgs", "unique_identifier_msgs"}
    result = build_package("test_msgs", tmp_path / "prefix", interfaces_dir=tmp_path / "interfaces")
    share = result.prefix / "share" / "test_msgs" / "action"
    assert sorted(p.name for p in share.iterdir()) == [
        "Fibonacci.action",
        "Fibonacci.idl",
        "Fibonacci.json",
    ]
    ours = _hashes(share / "Fibonacci.json")
    assert len(ours) == 16
    assert ours == _hashes(UPSTREAM_FIBONACCI / "Fibonacci.json")


def test_navigate_to_pose_is_nav2_jazzys() -> None:
    from nav2_msgs.action import NavigateToPose

    hashes = _hashes(SHARE / "nav2_msgs" / "action" / "NavigateToPose.json")
    assert hashes["nav2_msgs/action/NavigateToPose_FeedbackMessage"] == JAZZY_NAV2_FEEDBACK_HASH
    assert {f"nav2_msgs/action/NavigateToPose_{part}" for part in EXPANDED} <= set(hashes)
    assert NavigateToPose.Goal.get_fields_and_field_types() == {
        "pose": "geometry_msgs/PoseStamped",
        "behavior_tree": "string",
    }
    assert NavigateToPose.Result.get_fields_and_field_types() == {
        "error_code": "uint16",
        "error_msg": "string",
    }
    assert NavigateToPose.Result.NONE == 0
    assert list(NavigateToPose.Feedback.get_fields_and_field_types()) == [
        "current_pose",
        "navigation_time",
        "estimated_time_remaining",
        "number_of_recoveries",
        "distance_remaining",
    ]


def test_nav2s_behaviour_actions_are_jazzys() -> None:
    """Spin, BackUp and DriveOnHeading as nav2_msgs 1.3.x (Jazzy) declares them, field for
    field (their .action files are upstream's, unchanged), fully expanded as ament does."""
    from nav2_msgs.action import BackUp, DriveOnHeading, Spin

    assert Spin.Goal.get_fields_and_field_types() == {
        "target_yaw": "float",
        "time_allowance": "builtin_interfaces/Duration",
    }
    assert Spin.Feedback.get_fields_and_field_types() == {"angular_distance_traveled": "float"}
    straight = {
        "target": "geometry_msgs/Point",
        "speed": "float",
        "time_allowance": "builtin_interfaces/Duration",
    }
    for action in (BackUp, DriveOnHeading):
        assert action.Goal.get_fields_and_field_types() == straight
        assert action.Feedback.get_fields_and_field_types() == {"distance_traveled": "float"}
    for action in (Spin, BackUp, DriveOnHeading):
        assert action.Result.get_fields_and_field_types() == {
            "total_elapsed_time": "builtin_interfaces/Duration",
            "error_code": "uint16",
            "error_msg": "string",
        }
    assert (Spin.Result.COLLISION_AHEAD, BackUp.Result.COLLISION_AHEAD) == (703, 714)
    assert DriveOnHeading.Result.COLLISION_AHEAD == 723
    for name in ("Spin", "BackUp", "DriveOnHeading"):
        hashes = _hashes(SHARE / "nav2_msgs" / "action" / f"{name}.json")
        assert {f"nav2_msgs/action/{name}_{part}" for part in EXPANDED} <= set(hashes)


def test_hri_ids_list_and_amiros_actions_are_installed() -> None:
    from amiro_interfaces.action import Forward, MoveTo, RecognizeActivity, Run, Search
    from hri_msgs.msg import IdsList
    from rclpy.serialization import deserialize_message, serialize_message
    from rosidl_generator_py.import_type_support_impl import import_type_support

    for package in ("nav2_msgs", "hri_msgs", "amiro_interfaces"):  # what rclpy loads to use them
        assert import_type_support(package) is not None

    msg = IdsList(ids=["anna", "b1"])
    msg.header.frame_id = "map"
    back = deserialize_message(serialize_message(msg), IdsList)
    assert (back.header.frame_id, list(back.ids)) == ("map", ["anna", "b1"])
    assert MoveTo.Goal().approach == pytest.approx(0.8)  # the .action's default
    assert Run.Goal().priority == -1 and Run.Goal().payload_json == "{}"
    assert "person" in Search.Goal.get_fields_and_field_types()
    assert RecognizeActivity.Goal().confirmations == 3
    assert Forward.Goal().speed == 0.0 and "achieved" in Forward.Result.get_fields_and_field_types()
    assert MoveTo.Feedback.get_fields_and_field_types()["recoveries"] == "int32"
