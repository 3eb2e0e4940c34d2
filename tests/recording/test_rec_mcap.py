"""MCAP recording of an embedded run and its replay into a fresh bus."""

from __future__ import annotations

from pathlib import Path

import pytest
from mcap.reader import make_reader

from amiro.core.clock import SimClock
from amiro.core.config import ConfigError
from amiro.core.messages import LaserScan, Odometry
from amiro.core.runtime import Runtime
from amiro.recording.mcap_file import McapReplayer
from amiro.recording.runs import record_hydration, replay


@pytest.fixture(scope="module")
def recording(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, dict[str, object]]:
    out = tmp_path_factory.mktemp("rec") / "hydration.mcap"
    return out, record_hydration(out, seed=1, topics=["/scan", "/odom", "/amiro/events", "/tf"])


def test_file_has_ros2_schemas_that_foxglove_reads(
    recording: tuple[Path, dict[str, object]],
) -> None:
    path, report = recording
    assert report["outcome"] != "timeout" and report["messages"] > 1000
    with path.open("rb") as f:
        reader = make_reader(f)
        summary = reader.get_summary()
        assert summary is not None
        schemas = {s.name: s.encoding for s in summary.schemas.values()}
        channels = {c.topic: c.message_encoding for c in summary.channels.values()}
        assert reader.get_header().profile == "ros2"
    assert schemas["sensor_msgs/msg/LaserScan"] == "ros2msg"
    assert schemas["tf2_msgs/msg/TFMessage"] == "ros2msg"
    assert set(channels) == {"/scan", "/odom", "/amiro/events", "/tf"}
    assert set(channels.values()) == {"cdr"}


def test_replay_publishes_every_message_in_time_order(
    recording: tuple[Path, dict[str, object]],
) -> None:
    path, report = recording
    runtime = Runtime(SimClock())
    replayer = runtime.add(McapReplayer(path))
    scans: list[LaserScan] = []
    odoms: list[Odometry] = []
    runtime.bus.subscribe("/scan", LaserScan, scans.append, depth=10_000)
    runtime.bus.subscribe("/odom", Odometry, odoms.append, depth=10_000)
    runtime.start()
    runtime.spin_until(lambda: replayer.finished, 120.0)
    topics = report["topics"]
    assert isinstance(topics, dict)
    assert len(scans) == topics["/scan"] and len(odoms) == topics["/odom"]
    stamps = [s.header.stamp for s in scans]
    assert stamps == sorted(stamps) and len(scans[0].ranges) > 100
    assert runtime.clock.now() == pytest.approx(stamps[-1] - stamps[0], abs=0.2)


def test_replay_reports_counts_and_rejects_bad_files(
    recording: tuple[Path, dict[str, object]], tmp_path: Path
) -> None:
    path, report = recording
    result = replay(path)
    assert result["topics"] == report["topics"] and result["skipped"] == {}
    bad = tmp_path / "bad.mcap"
    bad.write_bytes(b"not an mcap file")
    with pytest.raises(ConfigError, match=r"bad\.mcap"):
        replay(bad)
    with pytest.raises(ConfigError, match="no such file"):
        replay(tmp_path / "missing.mcap")
