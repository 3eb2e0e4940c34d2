"""The robot's RGB-D camera as one frame at a time: the latest RGB image, the depth image
nearest to it in time, the intrinsics and the head joints when it was taken.

Every robot adapter publishes the robot port's camera topics (:mod:`amiro.core.names`):
``rgb8`` images, ``32FC1`` depth in metres (``16UC1`` millimetres are converted), the
camera info and the head's joint states.  Perception and activity both read frames from
one feed, so the images are converted once.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from amiro.core import names
from amiro.core.messages import CameraInfo, Image, JointState
from amiro.core.node import Node

FloatArray = npt.NDArray[np.float64]
DEPTH_HISTORY = 8  # depth images kept to pair with a later RGB image
JOINT_HISTORY = 64  # head joint states kept to find the one nearest an image in time


@dataclass(frozen=True, eq=False)
class RgbdFrame:
    """One RGB image with its registered depth image (metres, 0 = no reading), the
    intrinsics and the head angles (rad; pitch positive down) at ``stamp``."""

    stamp: float
    rgb: npt.NDArray[np.uint8]
    depth: FloatArray
    info: CameraInfo
    head_yaw: float
    head_pitch: float


def rgb_pixels(img: Image) -> npt.NDArray[np.uint8]:
    """The image as (H, W, 3) RGB; ``bgr8`` is reordered, other encodings refused."""
    data = np.asarray(img.data).reshape(img.height, img.width, -1)
    if img.encoding not in ("rgb8", "bgr8") or data.shape[2] != 3:
        raise ValueError(f"camera image encoding {img.encoding!r}: expected rgb8 or bgr8")
    rgb = data[:, :, ::-1] if img.encoding == "bgr8" else data
    return np.ascontiguousarray(rgb, dtype=np.uint8)


def depth_metres(img: Image) -> FloatArray:
    """The depth image in metres with 0 where there is no reading (NaN, inf, negative)."""
    data = np.asarray(img.data).reshape(img.height, img.width).astype(np.float64)
    if img.encoding == "16UC1":
        data = data / 1000.0
    elif img.encoding != "32FC1":
        raise ValueError(f"depth image encoding {img.encoding!r}: expected 32FC1 or 16UC1")
    out: FloatArray = np.where(np.isfinite(data) & (data > 0), data, 0.0)
    return out


class CameraFeed(Node):
    """Keeps the camera's latest messages; :meth:`latest` pairs them into a frame.

    ``yaw`` and ``pitch`` are the camera's angles on the base when no head joint states
    arrive (or ``head_joints`` is off): a fixed camera's extrinsic.  Otherwise the head
    angles are those of the joint state nearest in time to the image.
    """

    def __init__(
        self,
        yaw: float = 0.0,
        pitch: float = 0.0,
        head_joints: bool = True,
        max_skew_s: float = 0.1,
        name: str = "camera_feed",
    ) -> None:
        super().__init__(name)
        self.fixed = (yaw, pitch)
        self.head = {names.HEAD_YAW: yaw, names.HEAD_PITCH: pitch}
        self.head_history: deque[tuple[float, float, float]] = deque(maxlen=JOINT_HISTORY)
        self.head_joints = head_joints
        self.max_skew_s = max_skew_s
        self.rgb: tuple[float, Image] | None = None
        self.depths: deque[tuple[float, Image]] = deque(maxlen=DEPTH_HISTORY)
        self.info: CameraInfo | None = None
        self.bad_frames = 0  # images that could not be read

    def on_start(self) -> None:
        self.create_subscription(names.IMAGE, Image, self._on_rgb, depth=1)
        self.create_subscription(names.DEPTH, Image, self._on_depth, depth=DEPTH_HISTORY)
        self.create_subscription(names.CAMERA_INFO, CameraInfo, self._on_info, depth=1)
        if self.head_joints:
            self.create_subscription(names.JOINT_STATES, JointState, self._on_joints)

    def _on_rgb(self, msg: Image) -> None:
        self.rgb = (msg.header.stamp, msg)

    def _on_depth(self, msg: Image) -> None:
        self.depths.append((msg.header.stamp, msg))

    def _on_info(self, msg: CameraInfo) -> None:
        self.info = msg

    def _on_joints(self, msg: JointState) -> None:
        for name, position in zip(msg.name, msg.position, strict=False):
            if name in self.head:
                self.head[name] = float(position)
        stamp = msg.header.stamp
        self.head_history.append((stamp, self.head[names.HEAD_YAW], self.head[names.HEAD_PITCH]))

    def head_at(self, stamp: float) -> tuple[float, float]:
        """(yaw, pitch) of the joint state nearest to ``stamp``; the fixed angles if none."""
        if not self.head_history:
            return self.fixed
        _, yaw, pitch = min(self.head_history, key=lambda h: abs(h[0] - stamp))
        return yaw, pitch

    def latest(self, max_age_s: float | None = None) -> RgbdFrame | None:
        """The newest RGB image with the depth image nearest in time (within
        ``max_skew_s``); None until both and the camera info have arrived, when the pair
        is too far apart or older than ``max_age_s``, or when an image cannot be read."""
        if self.rgb is None or self.info is None or not self.depths:
            return None
        stamp, rgb = self.rgb
        if max_age_s is not None and self.now() - stamp > max_age_s:
            return None
        depth_stamp, depth = min(self.depths, key=lambda d: abs(d[0] - stamp))
        if abs(depth_stamp - stamp) > self.max_skew_s:
            return None
        try:
            pixels, metres = rgb_pixels(rgb), depth_metres(depth)
        except ValueError as exc:
            self.bad_frames += 1
            self.log.warning("camera frame dropped: %s", exc)
            return None
        return RgbdFrame(stamp, pixels, metres, self.info, *self.head_at(stamp))
