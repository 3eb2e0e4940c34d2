"""The residents' skeleton streams, as a pose estimator on Pepper's head camera gives them.

Each resident performs clips of their current activity at the model's frame rate:
synthetic motion from :mod:`amiro.activity.motion`, or real recorded motion
(``sim.skeletons.replay``, :mod:`amiro.activity.replay`) for the activities it has.  The
head camera sees the joints that project inside its image; coordinates are reported in
Kinect axes (x left, y up, z forward), the head's pitch undone from its joint angle.  Like a
real sensor (``sim.skeletons``, on by default) the stream jitters, loses joints, and comes
in a frame tilted by a pitch nobody corrected, so the recogniser's own view normalisation
has to level it.  Frames are generated lazily, when someone asks, up to the current
simulated time.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Iterable

import numpy as np
import numpy.typing as npt

from amiro.activity.labels import IDLE
from amiro.activity.lifting import level
from amiro.activity.motion import FPS, Body, perform
from amiro.activity.replay import load_motion
from amiro.activity.skeleton import NUM_JOINTS, FloatArray, J
from amiro.core.messages import CameraInfo, Pose2D
from amiro.robot.camera import Camera, CameraObservation
from amiro.sim.config import SkeletonsSection
from amiro.sim.residents import Resident
from amiro.sim.simulator import Simulation

HISTORY_S = 4.0
# What an occluding object (the scenario's "skeleton occluded") leaves visible.
OCCLUSION_VISIBLE = tuple(J[n] for n in ("Head", "Neck", "SpineShoulder", "ShoulderLeft"))


Motion = dict[str, list[FloatArray]]  # real body-frame clips by activity


class SkeletonStream:
    """One resident's body-frame skeletons, one per 1/FPS s of simulated time, with the
    sensor's jitter and lost joints."""

    def __init__(
        self,
        body: Body,
        rng: np.random.Generator,
        sensor: SkeletonsSection | None = None,
        motion: Motion | None = None,
    ) -> None:
        self.body = body
        self.rng = rng
        self.sensor = sensor or SkeletonsSection(noise_m=0.0, dropout=0.0, pitch_deg=0.0)
        self.motion = motion or {}
        self.last_clean: FloatArray | None = None
        self.frames: deque[FloatArray] = deque(maxlen=int(HISTORY_S * FPS))
        self.next_t: float | None = None
        self.pending: list[FloatArray] = []
        self.playing: tuple[str, bool] | None = None
        self.clips = 0  # clips generated since the activity or posture last changed
        self.count = 0  # frames made so far; the newest is number ``count``

    def advance(self, now: float, activity: str, sitting: bool) -> None:
        if self.next_t is None:
            self.next_t = now - HISTORY_S  # the camera has been watching already
        while self.next_t <= now:
            if self.playing != (activity, sitting):
                self.pending = []
                self.playing = (activity, sitting)
                self.clips = 0
            if not self.pending:
                self.pending = self._clip(activity, sitting)
                self.clips += 1
            self.last_clean = self.pending.pop(0)
            self.frames.append(self._sensed(self.last_clean))
            self.count += 1
            self.next_t += 1.0 / FPS

    def _sensed(self, frame: FloatArray) -> FloatArray:
        """One frame as the sensor gives it: jittered, some joints lost."""
        out = frame
        if self.sensor.noise_m > 0.0:
            out = out + self.rng.normal(0.0, self.sensor.noise_m, out.shape)
        if self.sensor.dropout > 0.0:
            out = out.copy()
            out[self.rng.random(NUM_JOINTS) < self.sensor.dropout] = np.nan
        return out

    def _clip(self, activity: str, sitting: bool) -> list[FloatArray]:
        if activity == "falling" and self.clips > 0 and self.last_clean is not None:
            return [self.last_clean]  # after the fall: lying still
        action = IDLE if activity == "idle" else activity
        recorded = self.motion.get(action)
        if recorded:
            return list(recorded[int(self.rng.integers(len(recorded)))])
        clip = list(perform(action, self.body, self.rng, FPS, sitting))
        if activity == "falling" and sitting:  # a seated person gets up, then falls
            return list(perform("standing_up", self.body, self.rng, FPS)) + clip
        return clip

    def last(self, n: int) -> FloatArray:
        return last_frames(self.frames, n)

    def since(self, count: int) -> FloatArray:
        """The frames made after frame number ``count`` (as many as the history keeps)."""
        n = min(self.count - count, len(self.frames))
        return np.stack(list(self.frames)[-n:])


def last_frames(frames: Iterable[FloatArray], n: int) -> FloatArray:
    """The last ``n`` of ``frames`` (at least one), the oldest repeated when fewer."""
    last = list(frames)[-n:]
    return np.stack([last[0]] * (n - len(last)) + last)


def to_level(camera: Camera, points: FloatArray, pose: Pose2D, head_yaw: float) -> FloatArray:
    """Map-frame points (..., 3) to the levelled camera frame (x left, y up, z forward)."""
    flat = points.reshape(-1, 3)
    level = camera.to_optical(flat, pose, head_yaw, 0.0) * np.array([-1.0, -1.0, 1.0])
    out: FloatArray = level.reshape(points.shape)
    return out


def from_level(camera: Camera, points: FloatArray, pose: Pose2D, head_yaw: float) -> FloatArray:
    """The inverse of :func:`to_level`: where levelled-camera points are in the map."""
    cx, cy, cz = camera.position(pose, head_yaw)
    yaw = pose.theta + head_yaw
    c, s = math.cos(yaw), math.sin(yaw)
    x, y, z = points[..., 0], points[..., 1], points[..., 2]
    return np.stack([cx + z * c - x * s, cy + z * s + x * c, cz + y], axis=-1)


def in_image(optical: FloatArray, info: CameraInfo) -> npt.NDArray[np.bool_]:
    """Which optical-frame points (N, 3) the camera images: ahead of it, inside the picture."""
    z = optical[:, 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        u = info.cx + info.fx * optical[:, 0] / z
        v = info.cy + info.fy * optical[:, 1] / z
    seen: npt.NDArray[np.bool_] = (
        (z > 0.1) & (u >= 0) & (u < info.width) & (v >= 0) & (v < info.height)
    )
    return seen


def body_to_map(frames: FloatArray, resident: Resident) -> FloatArray:
    """Body frame (x right, y up, z behind) to the map frame at the resident's pose."""
    c, s = np.cos(resident.heading), np.sin(resident.heading)
    forward = np.array([c, s, 0.0])
    right = np.array([s, -c, 0.0])
    up = np.array([0.0, 0.0, 1.0])
    out: FloatArray = (
        np.array([resident.x, resident.y, 0.0])
        + frames[..., :1] * right
        + frames[..., 1:2] * up
        - frames[..., 2:3] * forward
    )
    return out


def framing(
    observations: list[CameraObservation], person: str, image_height: float
) -> tuple[float, bool] | None:
    """(box height / image height, box clipped by the image's top or bottom), None unseen."""
    obs = next((o for o in observations if o.name == person), None)
    if obs is None:
        return None
    top = obs.bbox.cy - obs.bbox.height / 2.0
    bottom = obs.bbox.cy + obs.bbox.height / 2.0
    return obs.bbox.height / image_height, top <= 0.5 or bottom >= image_height - 0.5


class SkeletonCamera:
    """The skeleton source of the simulated robot (see :class:`SkeletonSource`)."""

    def __init__(
        self, sim: Simulation, rng: np.random.Generator, sensor: SkeletonsSection | None = None
    ) -> None:
        """``sensor``: default the simulation's ``sim.skeletons``."""
        self.sim = sim
        self.rng = rng
        self.sensor = sensor or sim.config.skeletons
        self.motion = load_motion(self.sensor.replay) if self.sensor.replay else {}
        self.streams: dict[str, SkeletonStream] = {}

    def framing(self, person: str) -> tuple[float, bool] | None:
        image_height = float(self.sim.residents.camera.params.image_height)
        return framing(self.sim.observe(), person, image_height)

    def window(self, person: str, frames: int) -> FloatArray | None:
        residents = self.sim.residents.residents
        if person not in residents or all(o.name != person for o in self.sim.observe()):
            return None
        stream = self._advance(person)
        return None if stream is None else self._tilted(self._view(stream.last(frames), person))

    def fresh(self, person: str, count: int) -> tuple[FloatArray, int] | None:
        """What the camera streams of ``person`` (known to be in view) since frame number
        ``count``: the frames as :meth:`window` gives them (from the view now) but levelled,
        without the sensor's tilt (the bridge carries them in ``camera_level``; the edge's
        feed tilts them as :meth:`window` does), and the newest frame's number."""
        stream = self._advance(person)
        if stream is None or stream.count <= count:
            return None
        return self._view(stream.since(count), person), stream.count

    def _advance(self, person: str) -> SkeletonStream | None:
        resident = self.sim.residents.residents.get(person)
        if resident is None:
            return None
        stream = self.streams.get(person)
        if stream is None:
            stream = self.streams[person] = SkeletonStream(
                Body.random(self.rng), self.rng, self.sensor, self.motion
            )
        sitting = resident.posture != "standing"
        stream.advance(self.sim.residents.now(), resident.activity, sitting)
        return stream

    def _view(self, body_frames: FloatArray, person: str) -> FloatArray:
        """Body-frame skeletons as the head camera sees them now (levelled, NaN unseen)."""
        resident = self.sim.residents.residents[person]
        frames = len(body_frames)
        points = body_to_map(body_frames, resident).reshape(-1, 3)
        robot, camera = self.sim.robot, self.sim.residents.camera
        pose, yaw = robot.true_pose, robot.head_yaw
        optical = camera.to_optical(points, pose, yaw, robot.head_pitch)
        seen = in_image(optical, camera.info(0.0))
        levelled = to_level(camera, points, pose, yaw)
        levelled[~seen] = np.nan
        out: FloatArray = levelled.reshape(frames, NUM_JOINTS, 3)
        if resident.skeleton_occluded:
            hidden = [j for j in range(NUM_JOINTS) if j not in OCCLUSION_VISIBLE]
            out[:, hidden] = np.nan
        return out

    def _tilted(self, frames: FloatArray) -> FloatArray:
        return sensor_tilt(frames, self.sensor.pitch_deg)


def sensor_tilt(frames: FloatArray, pitch_deg: float) -> FloatArray:
    """Levelled skeletons as a sensor pitched down by ``pitch_deg`` reports them."""
    out: FloatArray = level(frames, -math.radians(pitch_deg))
    return out
