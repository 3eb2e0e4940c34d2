"""The interface-package builder: tf2_msgs from its .msg file, built into a fresh prefix.

The build here goes to a temporary prefix (a few seconds), so these tests check the builder
itself whatever setup did to the venv; the live /tf tests use the venv's build.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from amiro.core.config import ConfigError
from amiro.ros2.env import ros_environment
from amiro.ros2.msgbuild import BuildResult, build_package
from amiro.ros2.msgbuild.__main__ import main
from amiro.ros2.msgbuild.compile import compiler
from amiro.ros2.msgbuild.install import is_current, site_packages
from amiro.ros2.msgbuild.package import load_package
from amiro.ros2.types import INTERFACES_DIR

# `ros2 topic info -v /tf` on an upstream ROS 2 Jazzy install
JAZZY_TFMESSAGE_HASH = "RIHS01_e369d0f05a23ae52508854b66f6aa0437f3449d652e8cbf22d5abe85d020f087"
LIB_KINDS = (
    "rosidl_generator_c",
    "rosidl_generator_py",
    "rosidl_typesupport_c",
    "rosidl_typesupport_fastrtps_c",
    "rosidl_typesupport_introspection_c",
)


@pytest.fixture(scope="module")
def built(tmp_path_factory: pytest.TempPathFactory) -> BuildResult:
    return build_package("tf2_msgs", tmp_path_factory.mktemp("prefix"))


def test_package_dependencies_come_from_the_fields() -> None:
    package = load_package("tf2_msgs")
    assert package.dependencies == ("geometry_msgs",)
    assert [p.as_posix() for p in package.interfaces] == ["msg/TFMessage.msg"]


def test_build_lays_out_an_installed_ros_package(built: BuildResult) -> None:
    prefix = built.prefix
    assert not built.skipped
    assert sorted(p.name for p in built.libraries) == [f"libtf2_msgs__{k}.so" for k in LIB_KINDS]
    assert all(p.is_file() for p in built.libraries)
    py = site_packages(prefix) / "tf2_msgs"
    assert (py / "msg" / "_tf_message.py").is_file()
    assert len(list(py.glob("tf2_msgs_s__rosidl_typesupport_*.so"))) == 3
    index = prefix / "share" / "ament_index" / "resource_index"
    assert (index / "packages" / "tf2_msgs").is_file()
    assert (index / "rosidl_interfaces" / "tf2_msgs").read_text().split() == [
        "msg/TFMessage.idl",
        "msg/TFMessage.msg",
    ]
    assert (prefix / "include" / "tf2_msgs" / "tf2_msgs" / "msg" / "tf_message.h").is_file()


def test_type_hash_is_upstream_jazzy(built: BuildResult) -> None:
    description = json.loads((built.prefix / "share/tf2_msgs/msg/TFMessage.json").read_text())
    hashes = {h["type_name"]: h["hash_string"] for h in description["type_hashes"]}
    assert hashes["tf2_msgs/msg/TFMessage"] == JAZZY_TFMESSAGE_HASH


def test_second_build_is_skipped_and_a_changed_definition_is_not(
    built: BuildResult, tmp_path: Path
) -> None:
    again = build_package("tf2_msgs", built.prefix)
    assert again.skipped and again.libraries == []
    edited = tmp_path / "tf2_msgs"
    shutil.copytree(INTERFACES_DIR / "tf2_msgs", edited)
    with (edited / "msg" / "TFMessage.msg").open("a") as f:
        f.write("int32 extra\n")
    assert is_current(load_package("tf2_msgs"), built.prefix)
    assert not is_current(load_package("tf2_msgs", tmp_path), built.prefix)


def _python(
    code: str, prefix: Path, env: dict[str, str] | None = None
) -> subprocess.CompletedProcess[str]:
    """Run ``code`` in a Python that finds the package built into ``prefix`` first."""
    full = {
        **os.environ,
        **(env or {}),
        "PYTHONPATH": str(site_packages(prefix)),
        # ahead of the venv's libraries (this process already set those up for rclpy)
        "LD_LIBRARY_PATH": os.pathsep.join([str(prefix / "lib"), os.environ["LD_LIBRARY_PATH"]]),
    }
    return subprocess.run(
        [sys.executable, "-c", code], env=full, capture_output=True, text=True, timeout=60
    )


PUBSUB = textwrap.dedent(
    """
    import json, time
    import rclpy
    import tf2_msgs
    from geometry_msgs.msg import TransformStamped
    from tf2_msgs.msg import TFMessage

    rclpy.init()
    node = rclpy.create_node("tf_check")
    got = []
    node.create_subscription(TFMessage, "/tf", got.append, 10)
    pub = node.create_publisher(TFMessage, "/tf", 10)
    t = TransformStamped()
    t.header.frame_id, t.child_frame_id = "odom", "base_link"
    t.transform.translation.x = 1.5
    deadline = time.monotonic() + 20
    while not got and time.monotonic() < deadline:
        pub.publish(TFMessage(transforms=[t]))
        rclpy.spin_once(node, timeout_sec=0.1)
    info = node.get_publishers_info_by_topic("/tf")[0]
    print(json.dumps({
        "module": tf2_msgs.__file__,
        "received": [[m.transforms[0].child_frame_id, m.transforms[0].transform.translation.x]
                     for m in got[:1]],
        "type": info.topic_type,
        "hash": str(info.topic_type_hash),
    }))
    """
)


def test_built_package_imports_and_travels_over_rclpy(built: BuildResult, domain_id: int) -> None:
    prefix = built.prefix
    done = _python(PUBSUB, prefix, ros_environment(domain_id))
    assert done.returncode == 0, done.stderr
    got = json.loads(done.stdout.strip().splitlines()[-1])
    assert got["module"].startswith(str(prefix))
    assert got["received"] == [["base_link", 1.5]]
    assert got["type"] == "tf2_msgs/msg/TFMessage"
    assert got["hash"] == JAZZY_TFMESSAGE_HASH


ROUNDTRIP = textwrap.dedent(
    """
    import json
    from rclpy.serialization import deserialize_message, serialize_message
    from demo_msgs.msg import Reading

    msg = Reading(values=[1.5, -2.0], label="kitchen")
    msg.header.frame_id = "map"
    back = deserialize_message(serialize_message(msg), Reading)
    print(json.dumps([back.header.frame_id, list(back.values), back.label]))
    """
)


def test_any_shipped_style_package_builds(tmp_path: Path) -> None:
    """The builder is generic: another package, other dependencies, primitive fields."""
    source = tmp_path / "interfaces" / "demo_msgs" / "msg"
    source.mkdir(parents=True)
    (source / "Reading.msg").write_text("std_msgs/Header header\nfloat64[] values\nstring label\n")
    package = load_package("demo_msgs", tmp_path / "interfaces")
    assert package.dependencies == ("std_msgs",)
    result = build_package("demo_msgs", tmp_path / "prefix", interfaces_dir=tmp_path / "interfaces")
    done = _python(ROUNDTRIP, result.prefix)
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout) == ["map", [1.5, -2.0], "kitchen"]


def test_unknown_package_is_one_line_and_exit_2(capsys: pytest.CaptureFixture[str]) -> None:
    shipped = "amiro_interfaces, audio_common_msgs, hri_msgs, nav2_msgs, tf2_msgs"
    with pytest.raises(ConfigError, match=rf"no interface package .nope.*shipped: {shipped}"):
        load_package("nope")
    assert main(["--package", "nope"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("error: no interface package")


def test_cli_reports_an_up_to_date_build_as_json(
    built: BuildResult, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["--package", "tf2_msgs", "--out", str(built.prefix), "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["packages"][0]["package"] == "tf2_msgs"
    assert report["packages"][0]["skipped"] is True


def test_missing_dependency_is_a_clear_error(tmp_path: Path) -> None:
    source = tmp_path / "demo_msgs" / "msg"
    source.mkdir(parents=True)
    (source / "Odd.msg").write_text("nowhere_msgs/Thing thing\n")
    with pytest.raises(ConfigError, match="demo_msgs needs nowhere_msgs, not installed"):
        build_package("demo_msgs", tmp_path / "prefix", interfaces_dir=tmp_path)


def test_missing_compiler_is_a_clear_error(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(shutil, "which", lambda _name: None)
    with pytest.raises(ConfigError, match="g\\+\\+ not found"):
        compiler(cxx=True)
