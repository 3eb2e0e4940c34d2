"""Where ROS 2 message classes come from: rclpy's generated modules or rosbags' typestore.

The converters in :mod:`amiro.ros2.convert` build messages through this small factory, so
the same code feeds a live rclpy publisher and an MCAP file written without any ROS install.
"""

from __future__ import annotations

import array
import importlib
from pathlib import Path
from typing import Any, Protocol

import numpy as np
import numpy.typing as npt


class MsgTypes(Protocol):
    def make(self, type_name: str, **fields: Any) -> Any:
        """A message of ``type_name`` ("sensor_msgs/msg/LaserScan") with these fields."""
        ...

    def float32_seq(self, values: npt.ArrayLike) -> Any:
        """An unbounded ``float32[]`` field value."""
        ...

    def float64_seq(self, values: npt.ArrayLike) -> Any:
        """An unbounded ``float64[]`` field value."""
        ...

    def int8_seq(self, values: npt.ArrayLike) -> Any:
        """An unbounded ``int8[]`` field value."""
        ...

    def int16_seq(self, values: npt.ArrayLike) -> Any:
        """An unbounded ``int16[]`` field value (audio samples)."""
        ...

    def int32_seq(self, values: npt.ArrayLike) -> Any:
        """An unbounded ``int32[]`` field value."""
        ...

    def uint8_seq(self, data: bytes) -> Any:
        """An unbounded ``uint8[]`` field value (image pixels)."""
        ...

    def available(self, type_name: str) -> bool: ...


class RclpyTypes:
    """Classes generated for rclpy (``sensor_msgs.msg.LaserScan``); sequences as array.array."""

    def __init__(self) -> None:
        self._cache: dict[str, Any] = {}

    def message_class(self, type_name: str) -> Any:
        cls = self._cache.get(type_name)
        if cls is None:
            package, kind, name = type_name.split("/")
            cls = getattr(importlib.import_module(f"{package}.{kind}"), name)
            self._cache[type_name] = cls
        return cls

    def make(self, type_name: str, **fields: Any) -> Any:
        return self.message_class(type_name)(**fields)

    def float32_seq(self, values: npt.ArrayLike) -> Any:
        return array.array("f", np.asarray(values, dtype=np.float32).tobytes())

    def float64_seq(self, values: npt.ArrayLike) -> Any:
        return array.array("d", np.asarray(values, dtype=np.float64).tobytes())

    def int8_seq(self, values: npt.ArrayLike) -> Any:
        return array.array("b", np.asarray(values, dtype=np.int8).tobytes())

    def int16_seq(self, values: npt.ArrayLike) -> Any:
        return array.array("h", np.asarray(values, dtype=np.int16).tobytes())

    def int32_seq(self, values: npt.ArrayLike) -> Any:
        return array.array("i", np.asarray(values, dtype=np.int32).tobytes())

    def uint8_seq(self, data: bytes) -> Any:
        return array.array("B", data)

    def available(self, type_name: str) -> bool:
        try:
            self.message_class(type_name)
        except (ImportError, AttributeError, ValueError):
            return False
        return True


# The .msg sources of the interface packages amiro ships (built for rclpy by msgbuild).
INTERFACES_DIR = Path(__file__).resolve().parents[1] / "data" / "ros2_interfaces"


class RosbagsTypes:
    """rosbags' pure-Python typestore (ROS 2 Jazzy definitions, and the interface packages
    amiro ships that Jazzy's store lacks: audio_common_msgs); sequences as numpy arrays."""

    def __init__(self) -> None:
        from rosbags.typesys import Stores, get_types_from_msg, get_typestore

        self.store = get_typestore(Stores.ROS2_JAZZY)
        shipped: dict[str, Any] = {}
        for msg in sorted(INTERFACES_DIR.glob("*/msg/*.msg")):
            name = f"{msg.parent.parent.name}/msg/{msg.stem}"
            if name not in self.store.types:
                shipped.update(get_types_from_msg(msg.read_text("utf-8"), name))
        self.store.register(shipped)

    def make(self, type_name: str, **fields: Any) -> Any:
        return self.store.types[type_name](**fields)

    def float32_seq(self, values: npt.ArrayLike) -> Any:
        return np.asarray(values, dtype=np.float32)

    def float64_seq(self, values: npt.ArrayLike) -> Any:
        return np.asarray(values, dtype=np.float64)

    def int8_seq(self, values: npt.ArrayLike) -> Any:
        return np.asarray(values, dtype=np.int8)

    def int16_seq(self, values: npt.ArrayLike) -> Any:
        return np.asarray(values, dtype=np.int16)

    def int32_seq(self, values: npt.ArrayLike) -> Any:
        return np.asarray(values, dtype=np.int32)

    def uint8_seq(self, data: bytes) -> Any:
        return np.frombuffer(data, dtype=np.uint8).copy()

    def available(self, type_name: str) -> bool:
        return type_name in self.store.types
