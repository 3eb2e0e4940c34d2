"""The robot choice in configuration, and camera images crossing from a driver."""

from __future__ import annotations

import numpy as np
import pytest

from amiro.core.config import ConfigError, parse
from amiro.core.messages import CameraInfo, Header, Image
from amiro.core.runtime import Runtime
from amiro.robot.build import build_robot
from amiro.robot.config import RobotConfig
from amiro.ros2.convert import bus_camera_info, bus_image, ros_camera_info, ros_image
from amiro.ros2.types import RosbagsTypes


def test_pepper_hybrid_hands_speech_tablet_head_posture_to_naoqi() -> None:
    cfg = parse(RobotConfig, {"adapter": "ros2", "naoqi": {"url": "tcp://p:9559"}}, "robot")
    assert cfg.naoqi_channels() == ("say", "display", "head", "posture")
    alone = parse(RobotConfig, {"adapter": "naoqi", "naoqi": {"url": "tcp://p:9559"}}, "robot")
    assert "base" in alone.naoqi_channels() and "odom" in alone.naoqi_channels()
    assert parse(RobotConfig, {}, "robot").adapter == "sim"


def test_inconsistent_robot_choices_are_one_line_errors() -> None:
    with pytest.raises(ConfigError, match=r"adapter naoqi needs naoqi\.url"):
        parse(RobotConfig, {"adapter": "naoqi"}, "robot")
    with pytest.raises(ConfigError, match="drop odom"):
        parse(RobotConfig, {"adapter": "ros2", "naoqi": {"handles": ["odom"]}}, "robot")
    with pytest.raises(ConfigError, match="robot: adapter"):
        parse(RobotConfig, {"adapter": "webots"}, "robot")
    with pytest.raises(ConfigError, match="not a NAOqi robot"):
        cfg = {"adapter": "ros2", "profile": "generic_diff", "naoqi": {"handles": ["say"]}}
        build_robot(Runtime(), parse(RobotConfig, cfg, "robot"))


def test_depth_in_millimetres_with_padded_rows_becomes_metres() -> None:
    types = RosbagsTypes()
    mm = np.array([[1000, 0, 2500], [40, 65535, 7]], dtype="<u2")
    padded = np.zeros((2, 8), dtype=np.uint8)  # step 8 > 3 pixels * 2 bytes
    padded[:, :6] = mm.view(np.uint8).reshape(2, 6)
    msg = types.make(
        "sensor_msgs/msg/Image",
        header=types.make(
            "std_msgs/msg/Header",
            stamp=types.make("builtin_interfaces/msg/Time", sec=1, nanosec=0),
            frame_id="cam",
        ),
        height=2, width=3, encoding="16UC1", is_bigendian=0, step=8,
        data=types.uint8_seq(padded.tobytes()),
    )  # fmt: skip
    img = bus_image(msg)
    assert img.encoding == "32FC1" and img.data.shape == (2, 3)
    assert img.data[0, 0] == pytest.approx(1.0) and np.isnan(img.data[0, 1])
    assert img.data[1, 1] == pytest.approx(65.535)
    back = bus_image(ros_image(types, img, 0.0))
    assert np.array_equal(back.data, img.data, equal_nan=True)
    with pytest.raises(ValueError, match="too short"):
        bus_image(msg.__class__(**{**msg.__dict__, "height": 5}))
    with pytest.raises(ValueError, match="cannot send"):
        ros_image(types, Image(Header(), 1, 1, "yuv422", np.zeros(2)), 0.0)


def test_camera_intrinsics_cross_both_ways() -> None:
    types = RosbagsTypes()
    k = (525.0, 0.0, 319.5, 0.0, 525.0, 239.5, 0.0, 0.0, 1.0)
    info = bus_camera_info(
        ros_camera_info(types, CameraInfo(Header(2.0, "camera"), 640, 480, k), 0)
    )
    assert (info.width, info.height, info.k, info.header.frame_id) == (640, 480, k, "camera")
