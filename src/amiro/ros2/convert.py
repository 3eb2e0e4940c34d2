"""Codecs between bus messages and ROS 2 standard messages (REP-103 units, REP-105 frames).

Each :class:`Codec` pairs a bus dataclass with a ROS 2 type.  Standard types map field by
field; amiro's own messages travel as ``std_msgs/String`` holding JSON, as the contract does
for ``/amiro/events``, so no custom interface package has to be built on either side.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Generic, TypeVar

import numpy as np
from pydantic import TypeAdapter

from amiro.core.messages import (
    SKELETON_JOINTS,
    AudioStamped,
    BehaviorEvent,
    CameraInfo,
    Header,
    Image,
    JointState,
    LaserScan,
    MapMetaData,
    OccupancyGrid,
    Odometry,
    Point,
    Pose,
    Pose2D,
    PoseStamped,
    Quaternion,
    Skeleton,
    SpeechRequest,
    String,
    TransformStamped,
    Twist,
    Vector3,
)
from amiro.ros2.types import MsgTypes

M = TypeVar("M")

STRING = "std_msgs/msg/String"


@dataclass(frozen=True)
class Codec(Generic[M]):
    """How one bus type crosses to ROS 2: ``encode(types, msg, now)`` and ``decode(ros)``."""

    bus_type: type[M]
    ros_type: str
    encode: Callable[[MsgTypes, M, float], Any]
    decode: Callable[[Any], M]


# --- builtin and std ------------------------------------------------------------------------


def ros_time(types: MsgTypes, t: float) -> Any:
    sec = math.floor(t)
    nanosec = min(round((t - sec) * 1e9), 999_999_999)
    return types.make("builtin_interfaces/msg/Time", sec=int(sec), nanosec=nanosec)


def seconds(stamp: Any) -> float:
    return float(stamp.sec) + float(stamp.nanosec) * 1e-9


def ros_header(types: MsgTypes, header: Header) -> Any:
    return types.make(
        "std_msgs/msg/Header", stamp=ros_time(types, header.stamp), frame_id=header.frame_id
    )


def bus_header(header: Any) -> Header:
    return Header(seconds(header.stamp), str(header.frame_id))


def _vector(types: MsgTypes, v: Vector3 | Point, type_name: str) -> Any:
    return types.make(type_name, x=float(v.x), y=float(v.y), z=float(v.z))


def _quaternion(types: MsgTypes, q: Quaternion) -> Any:
    return types.make(
        "geometry_msgs/msg/Quaternion", x=float(q.x), y=float(q.y), z=float(q.z), w=float(q.w)
    )


def ros_pose(types: MsgTypes, pose: Pose) -> Any:
    return types.make(
        "geometry_msgs/msg/Pose",
        position=_vector(types, pose.position, "geometry_msgs/msg/Point"),
        orientation=_quaternion(types, pose.orientation),
    )


def bus_pose(pose: Any) -> Pose:
    p, q = pose.position, pose.orientation
    return Pose(
        Point(float(p.x), float(p.y), float(p.z)),
        Quaternion(float(q.x), float(q.y), float(q.z), float(q.w)),
    )


def ros_twist(types: MsgTypes, twist: Twist, now: float = 0.0) -> Any:
    return types.make(
        "geometry_msgs/msg/Twist",
        linear=_vector(types, twist.linear, "geometry_msgs/msg/Vector3"),
        angular=_vector(types, twist.angular, "geometry_msgs/msg/Vector3"),
    )


def bus_twist(twist: Any) -> Twist:
    lin, ang = twist.linear, twist.angular
    return Twist(
        Vector3(float(lin.x), float(lin.y), float(lin.z)),
        Vector3(float(ang.x), float(ang.y), float(ang.z)),
    )


# --- sensor, nav and geometry messages --------------------------------------------------------


def ros_scan(types: MsgTypes, scan: LaserScan, now: float) -> Any:
    return types.make(
        "sensor_msgs/msg/LaserScan",
        header=ros_header(types, scan.header),
        angle_min=float(scan.angle_min),
        angle_max=float(scan.angle_max),
        angle_increment=float(scan.angle_increment),
        time_increment=float(scan.time_increment),
        scan_time=float(scan.scan_time),
        range_min=float(scan.range_min),
        range_max=float(scan.range_max),
        ranges=types.float32_seq(scan.ranges),
        intensities=types.float32_seq(()),
    )


def bus_scan(msg: Any) -> LaserScan:
    return LaserScan(
        bus_header(msg.header),
        float(msg.angle_min),
        float(msg.angle_max),
        float(msg.angle_increment),
        float(msg.time_increment),
        float(msg.scan_time),
        float(msg.range_min),
        float(msg.range_max),
        np.asarray(msg.ranges, dtype=np.float64),
    )


def ros_odometry(types: MsgTypes, odom: Odometry, now: float) -> Any:
    covariance = np.zeros(36, dtype=np.float64)
    return types.make(
        "nav_msgs/msg/Odometry",
        header=ros_header(types, odom.header),
        child_frame_id=odom.child_frame_id,
        pose=types.make(
            "geometry_msgs/msg/PoseWithCovariance",
            pose=ros_pose(types, odom.pose),
            covariance=covariance,
        ),
        twist=types.make(
            "geometry_msgs/msg/TwistWithCovariance",
            twist=ros_twist(types, odom.twist),
            covariance=covariance.copy(),
        ),
    )


def bus_odometry(msg: Any) -> Odometry:
    return Odometry(
        bus_header(msg.header),
        str(msg.child_frame_id),
        bus_pose(msg.pose.pose),
        bus_twist(msg.twist.twist),
    )


def ros_pose_stamped(types: MsgTypes, msg: PoseStamped, now: float) -> Any:
    return types.make(
        "geometry_msgs/msg/PoseStamped",
        header=ros_header(types, msg.header),
        pose=ros_pose(types, msg.pose),
    )


def bus_pose_stamped(msg: Any) -> PoseStamped:
    return PoseStamped(bus_header(msg.header), bus_pose(msg.pose))


def ros_pose2d(types: MsgTypes, pose: Pose2D, now: float) -> Any:
    """A planar pose in the map frame travels as a PoseStamped stamped with the sender's now."""
    return ros_pose_stamped(types, PoseStamped(Header(now, "map"), pose.to_pose()), now)


def bus_pose2d(msg: Any) -> Pose2D:
    return bus_pose(msg.pose).to_pose2d()


def ros_grid(types: MsgTypes, grid: OccupancyGrid, now: float) -> Any:
    info = grid.info
    return types.make(
        "nav_msgs/msg/OccupancyGrid",
        header=ros_header(types, grid.header),
        info=types.make(
            "nav_msgs/msg/MapMetaData",
            map_load_time=ros_time(types, grid.header.stamp),
            resolution=float(info.resolution),
            width=int(info.width),
            height=int(info.height),
            origin=ros_pose(types, info.origin),
        ),
        data=types.int8_seq(np.asarray(grid.data).ravel()),
    )


def bus_grid(msg: Any) -> OccupancyGrid:
    info = msg.info
    data = np.asarray(msg.data, dtype=np.int8).reshape(int(info.height), int(info.width))
    meta = MapMetaData(
        float(info.resolution), int(info.width), int(info.height), bus_pose(info.origin)
    )
    return OccupancyGrid(bus_header(msg.header), meta, data)


def ros_joints(types: MsgTypes, msg: JointState, now: float) -> Any:
    return types.make(
        "sensor_msgs/msg/JointState",
        header=ros_header(types, msg.header),
        name=list(msg.name),
        position=types.float64_seq(msg.position),
        velocity=types.float64_seq(()),
        effort=types.float64_seq(()),
    )


def bus_joints(msg: Any) -> JointState:
    return JointState(
        bus_header(msg.header),
        tuple(str(n) for n in msg.name),
        tuple(float(p) for p in msg.position),
    )


def ros_tf(types: MsgTypes, tf: TransformStamped, now: float) -> Any:
    transform = types.make(
        "geometry_msgs/msg/TransformStamped",
        header=ros_header(types, tf.header),
        child_frame_id=tf.child_frame_id,
        transform=types.make(
            "geometry_msgs/msg/Transform",
            translation=_vector(types, tf.translation, "geometry_msgs/msg/Vector3"),
            rotation=_quaternion(types, tf.rotation),
        ),
    )
    return types.make("tf2_msgs/msg/TFMessage", transforms=[transform])


def bus_tf(msg: Any) -> TransformStamped:
    """The first transform of a TFMessage (amiro publishes one transform per message)."""
    t = msg.transforms[0]
    tr, rot = t.transform.translation, t.transform.rotation
    return TransformStamped(
        bus_header(t.header),
        str(t.child_frame_id),
        Vector3(float(tr.x), float(tr.y), float(tr.z)),
        Quaternion(float(rot.x), float(rot.y), float(rot.z), float(rot.w)),
    )


# --- camera images -----------------------------------------------------------------------

# ROS encoding -> (numpy dtype, channels); the bus keeps rgb8, mono8 and 32FC1 depth in metres.
_PIXELS: dict[str, tuple[str, int]] = {
    "rgb8": ("u1", 3),
    "bgr8": ("u1", 3),
    "mono8": ("u1", 1),
    "16UC1": ("u2", 1),
    "32FC1": ("f4", 1),
}


def ros_image(types: MsgTypes, img: Image, now: float) -> Any:
    if img.encoding not in _PIXELS:
        raise ValueError(f"cannot send an image encoded {img.encoding}")
    data = np.ascontiguousarray(
        img.data, dtype=np.dtype(_PIXELS[img.encoding][0]).newbyteorder("<")
    )
    return types.make(
        "sensor_msgs/msg/Image",
        header=ros_header(types, img.header),
        height=int(img.height),
        width=int(img.width),
        encoding=img.encoding,
        is_bigendian=0,
        step=int(data.nbytes // max(img.height, 1)),
        data=types.uint8_seq(data.tobytes()),
    )


def bus_image(msg: Any) -> Image:
    """Pixels as an array; bgr8 becomes rgb8 and 16UC1 depth (mm) becomes 32FC1 (m, 0 -> NaN)."""
    encoding = str(msg.encoding)
    if encoding not in _PIXELS:
        raise ValueError(f"unsupported image encoding {encoding}")
    kind, channels = _PIXELS[encoding]
    height, width, step = int(msg.height), int(msg.width), int(msg.step)
    dtype = np.dtype(kind).newbyteorder(">" if msg.is_bigendian else "<")
    row = width * channels * dtype.itemsize
    raw = np.frombuffer(bytes(msg.data), dtype=np.uint8)
    if step < row or raw.size < step * height:
        raise ValueError(f"image data too short for {width}x{height} {encoding}")
    rows = raw[: step * height].reshape(height, step)[:, :row]
    pixels = np.ascontiguousarray(rows).view(dtype).reshape(height, width, channels)
    if channels == 1:
        pixels = pixels[:, :, 0]
    if encoding == "bgr8":
        pixels, encoding = pixels[:, :, ::-1], "rgb8"
    elif encoding == "16UC1":
        metres = pixels.astype(np.float32) / 1000.0
        pixels, encoding = np.where(pixels == 0, np.float32(np.nan), metres), "32FC1"
    return Image(bus_header(msg.header), height, width, encoding, np.ascontiguousarray(pixels))


def ros_camera_info(types: MsgTypes, info: CameraInfo, now: float) -> Any:
    k = [float(v) for v in info.k]
    return types.make(
        "sensor_msgs/msg/CameraInfo",
        header=ros_header(types, info.header),
        height=int(info.height),
        width=int(info.width),
        distortion_model="plumb_bob",
        d=types.float64_seq(np.zeros(5)),
        k=np.asarray(k, dtype=np.float64),
        r=np.eye(3).ravel(),
        p=np.asarray([k[0], k[1], k[2], 0.0, k[3], k[4], k[5], 0.0, 0.0, 0.0, 1.0, 0.0]),
        binning_x=0,
        binning_y=0,
        roi=types.make(
            "sensor_msgs/msg/RegionOfInterest",
            x_offset=0,
            y_offset=0,
            height=0,
            width=0,
            do_rectify=False,
        ),
    )


def bus_camera_info(msg: Any) -> CameraInfo:
    values = [float(v) for v in msg.k]
    if len(values) != 9:
        raise ValueError("CameraInfo.k must have 9 values")
    k0, k1, k2, k3, k4, k5, k6, k7, k8 = values
    k = (k0, k1, k2, k3, k4, k5, k6, k7, k8)
    return CameraInfo(bus_header(msg.header), int(msg.width), int(msg.height), k)


# --- strings and JSON-carrying messages --------------------------------------------------


def ros_string(types: MsgTypes, msg: String, now: float) -> Any:
    return types.make(STRING, data=msg.data)


def bus_string(msg: Any) -> String:
    return String(str(msg.data))


def json_codec(bus_type: type[M]) -> Codec[M]:
    """A dataclass as JSON in a ``std_msgs/String``, validated on the way in by pydantic."""
    adapter: TypeAdapter[M] = TypeAdapter(bus_type)

    def encode(types: MsgTypes, msg: M, now: float) -> Any:
        return types.make(STRING, data=adapter.dump_json(msg).decode())

    def decode(msg: Any) -> M:
        return adapter.validate_json(str(msg.data))

    return Codec(bus_type, STRING, encode, decode)


def ros_event(types: MsgTypes, event: BehaviorEvent, now: float) -> Any:
    """The contract's ``/amiro/events``: the flat dictionary the logs and dashboard show."""
    return types.make(STRING, data=json.dumps(event.to_dict(), default=str))


def bus_event(msg: Any) -> BehaviorEvent:
    data = json.loads(str(msg.data))
    if not isinstance(data, dict) or not isinstance(data.get("type"), str):
        raise ValueError("an event is a JSON object with a string 'type'")
    stamp = float(data.pop("t", 0.0))
    kind = data.pop("type")
    graph, task = data.pop("graph", None), data.pop("task", None)
    return BehaviorEvent(stamp, kind, graph, task, data)


_SPEECH = TypeAdapter(SpeechRequest)


def ros_say(types: MsgTypes, msg: SpeechRequest, now: float) -> Any:
    return types.make(STRING, data=_SPEECH.dump_json(msg).decode())


def bus_say(msg: Any) -> SpeechRequest:
    """``/amiro/say`` carries a SpeechRequest as JSON; plain text from any ROS tool works too."""
    text = str(msg.data)
    if text.lstrip().startswith("{"):
        return _SPEECH.validate_json(text)
    return SpeechRequest(text=text)


SKELETON_KEYS = frozenset({"stamp", "frame_id", "body_id", "joints", "tracked"})


def ros_skeleton(types: MsgTypes, msg: Skeleton, now: float) -> Any:
    """An NTU skeleton as JSON (no standard ROS type has one): untracked joints are zeros."""
    joints = np.where(msg.tracked[:, None], msg.joints, 0.0)
    data = {
        "stamp": msg.header.stamp,
        "frame_id": msg.header.frame_id,
        "body_id": msg.body_id,
        "joints": [round(float(v), 5) for v in joints.ravel()],
        "tracked": [bool(t) for t in msg.tracked],
    }
    return types.make(STRING, data=json.dumps(data))


def bus_skeleton(msg: Any) -> Skeleton:
    data = json.loads(str(msg.data))
    if not isinstance(data, dict) or not data.keys() >= SKELETON_KEYS:
        raise ValueError(f"a skeleton is a JSON object with {', '.join(sorted(SKELETON_KEYS))}")
    joints = np.asarray(data["joints"], dtype=np.float64)
    tracked = np.asarray(data["tracked"], dtype=np.bool_)
    if joints.shape != (3 * SKELETON_JOINTS,) or tracked.shape != (SKELETON_JOINTS,):
        raise ValueError(
            f"a skeleton has {SKELETON_JOINTS} joints of x, y, z and a tracked flag each"
        )
    header = Header(float(data["stamp"]), str(data["frame_id"]))
    return Skeleton(header, int(data["body_id"]), joints.reshape(SKELETON_JOINTS, 3), tracked)


# --- audio (audio_common_msgs, mgonzs13/audio_common 4.0: the type whisper_ros hears) --------

AUDIO_STAMPED = "audio_common_msgs/msg/AudioStamped"
# PyAudio's sample formats, which AudioInfo.format carries: the AudioData field holding them
# and the scale to 16-bit.
_AUDIO_FORMATS: dict[int, tuple[str, float]] = {
    1: ("float32_data", 32767.0),  # paFloat32, -1..1
    2: ("int32_data", 1.0 / 65536.0),  # paInt32
    8: ("int16_data", 1.0),  # paInt16
    16: ("int8_data", 256.0),  # paInt8
}
PA_INT16 = 8
PA_UINT8 = 32


def ros_audio(types: MsgTypes, msg: AudioStamped, now: float) -> Any:
    """Mono 16-bit samples as ``int16_data`` (format paInt16), one chunk per message."""
    samples = np.asarray(msg.samples, dtype=np.int16)
    data = types.make(
        "audio_common_msgs/msg/AudioData",
        float32_data=types.float32_seq([]),
        int32_data=types.int32_seq([]),
        int16_data=types.int16_seq(samples),
        int8_data=types.int8_seq([]),
        uint8_data=types.uint8_seq(b""),
    )
    info = types.make(
        "audio_common_msgs/msg/AudioInfo",
        format=PA_INT16,
        channels=1,
        rate=int(msg.rate),
        chunk=len(samples),
    )
    audio = types.make("audio_common_msgs/msg/Audio", audio_data=data, info=info)
    return types.make(AUDIO_STAMPED, header=ros_header(types, msg.header), audio=audio)


def bus_audio(msg: Any) -> AudioStamped:
    """Any of PyAudio's integer or float formats, any channel count (averaged to mono)."""
    info, data = msg.audio.info, msg.audio.audio_data
    fmt, channels, rate = int(info.format), int(info.channels), int(info.rate)
    if rate <= 0 or channels <= 0:
        raise ValueError(f"audio at {rate} Hz with {channels} channels")
    if fmt == PA_UINT8:
        x = (np.asarray(data.uint8_data, dtype=np.float64) - 128.0) * 256.0
    elif fmt in _AUDIO_FORMATS:
        field_name, scale = _AUDIO_FORMATS[fmt]
        x = np.asarray(getattr(data, field_name), dtype=np.float64) * scale
    else:
        raise ValueError(f"unsupported audio format {fmt} (PyAudio's paInt16 = {PA_INT16})")
    if len(x) % channels:
        raise ValueError(f"{len(x)} samples do not split into {channels} channels")
    mono = x.reshape(-1, channels).mean(axis=1)
    samples = np.clip(np.round(mono), -32768, 32767).astype(np.int16)
    return AudioStamped(bus_header(msg.header), samples, rate)


STANDARD_CODECS: tuple[Codec[Any], ...] = (
    Codec(LaserScan, "sensor_msgs/msg/LaserScan", ros_scan, bus_scan),
    Codec(Odometry, "nav_msgs/msg/Odometry", ros_odometry, bus_odometry),
    Codec(Twist, "geometry_msgs/msg/Twist", ros_twist, bus_twist),
    Codec(PoseStamped, "geometry_msgs/msg/PoseStamped", ros_pose_stamped, bus_pose_stamped),
    Codec(Pose2D, "geometry_msgs/msg/PoseStamped", ros_pose2d, bus_pose2d),
    Codec(OccupancyGrid, "nav_msgs/msg/OccupancyGrid", ros_grid, bus_grid),
    Codec(JointState, "sensor_msgs/msg/JointState", ros_joints, bus_joints),
    Codec(TransformStamped, "tf2_msgs/msg/TFMessage", ros_tf, bus_tf),
    Codec(Image, "sensor_msgs/msg/Image", ros_image, bus_image),
    Codec(CameraInfo, "sensor_msgs/msg/CameraInfo", ros_camera_info, bus_camera_info),
    Codec(String, STRING, ros_string, bus_string),
    Codec(BehaviorEvent, STRING, ros_event, bus_event),
    Codec(SpeechRequest, STRING, ros_say, bus_say),
    Codec(Skeleton, STRING, ros_skeleton, bus_skeleton),
    Codec(AudioStamped, AUDIO_STAMPED, ros_audio, bus_audio),
)
