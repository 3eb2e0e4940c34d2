"""The microphone topic over ROS 2: audio_common_msgs/AudioStamped (mgonzs13/audio_common
4.0, what whisper_ros subscribes to) built from amiro's copy of its .msg files, its type
hashes those of the upstream definitions, and the codec both ways; which topics a process
that hears audio exports and imports."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pytest

from amiro.core import names
from amiro.core.messages import AudioStamped, Header
from amiro.deploy.config import NodeConfig
from amiro.ros2.convert import AUDIO_STAMPED, bus_audio
from amiro.ros2.routes import route
from amiro.ros2.types import RclpyTypes, RosbagsTypes

# The RIHS01 hashes of upstream's definitions (audio_common_msgs 4.0.10, commit f0767f3),
# computed by rosbags from upstream's .msg files.
UPSTREAM_HASHES = {
    "audio_common_msgs/msg/AudioStamped": (
        "RIHS01_f6ad36427cfe3e7132f91509dca5a3be31b9b681f182db6e606e95e781b21611"
    ),
    "audio_common_msgs/msg/Audio": (
        "RIHS01_56bb1432a8bc1cf3579fa7dcfa6107180f29e799b30e51a880e5591ccc789de2"
    ),
    "audio_common_msgs/msg/AudioData": (
        "RIHS01_28873bc02f2963cbc2e6e7dbadd149384f99daddba98ddc2a7cd2550a0b9b5c3"
    ),
    "audio_common_msgs/msg/AudioInfo": (
        "RIHS01_2418e6f9b3639c2844652701c489705b045d5b970c0674573a0f668d6af3b58b"
    ),
}
CHUNK = AudioStamped(
    Header(12.5, "microphone"),
    (np.sin(np.arange(8000) / 7.0) * 12000).astype(np.int16),
    16000,
)


def _same(a: AudioStamped, b: AudioStamped) -> None:
    assert b.header == a.header and b.rate == a.rate
    assert np.array_equal(b.samples, a.samples)


def test_the_built_package_has_the_upstream_type_hashes() -> None:
    description = Path(sys.prefix) / "share/audio_common_msgs/msg/AudioStamped.json"
    built = {
        h["type_name"]: h["hash_string"] for h in json.loads(description.read_text())["type_hashes"]
    }
    store = RosbagsTypes().store
    for name, expected in UPSTREAM_HASHES.items():
        assert built[name] == store.hash_rihs01(name) == expected


def test_audio_crosses_through_rclpy_and_rosbags_cdr() -> None:
    codec = route(names.AUDIO).codec
    assert codec.ros_type == AUDIO_STAMPED
    _same(CHUNK, codec.decode(codec.encode(RclpyTypes(), CHUNK, 0.0)))
    types = RosbagsTypes()
    raw = types.store.serialize_cdr(codec.encode(types, CHUNK, 0.0), AUDIO_STAMPED)
    _same(CHUNK, codec.decode(types.store.deserialize_cdr(raw, AUDIO_STAMPED)))


def _foreign(fmt: int, channels: int, **data: object) -> object:
    """A message as another driver would send it (PyAudio's format codes)."""
    t = RclpyTypes()
    audio = t.make(
        "audio_common_msgs/msg/Audio",
        audio_data=t.make("audio_common_msgs/msg/AudioData", **data),
        info=t.make(
            "audio_common_msgs/msg/AudioInfo", format=fmt, channels=channels, rate=44100, chunk=2
        ),
    )
    return t.make(AUDIO_STAMPED, audio=audio)


def test_other_drivers_formats_become_16_bit_mono() -> None:
    stereo = _foreign(1, 2, float32_data=[0.5, -0.5, 1.0, 0.0])  # paFloat32, 2 frames
    got = bus_audio(stereo)
    assert got.rate == 44100 and got.samples.tolist() == [0, 16384]
    assert bus_audio(_foreign(32, 1, uint8_data=[128, 255])).samples.tolist() == [0, 32512]
    assert bus_audio(_foreign(2, 1, int32_data=[65536 * 100])).samples.tolist() == [100]
    with pytest.raises(ValueError, match="unsupported audio format 4"):
        bus_audio(_foreign(4, 1, uint8_data=[0, 0, 0]))  # paInt24
    with pytest.raises(ValueError, match="do not split into 2 channels"):
        bus_audio(_foreign(8, 2, int16_data=[1, 2, 3]))


def test_a_process_that_hears_audio_swaps_text_for_audio() -> None:
    sim = NodeConfig(role="sim", hear_audio=True)
    assert names.AUDIO in sim.topics_out() and names.HEARD not in sim.topics_out()
    assert names.HEARD in NodeConfig(role="sim").topics_out()
    cloud = NodeConfig(role="cloud", hear_audio=True)
    assert names.HEARD in cloud.topics_out()
    assert {names.AUDIO, names.SAY} <= set(cloud.topics_in())
    edge = NodeConfig(role="edge", hear_audio=True)  # says itself: /amiro/say is its own
    assert names.AUDIO in edge.topics_in() and names.HEARD not in edge.topics_in()
    assert names.SAY not in edge.topics_in()
