"""The residents' skeleton streams, as a pose estimator on Pepper's head camera gives them.

Each resident performs clips of their current activity (synthetic motion from
:mod:`amiro.activity.motion`) at the model's frame rate.  The head camera sees the joints
that project inside its image; coordinates are reported in a levelled camera frame
(Kinect axes: x left, y up, z forward), the head's pitch undone from its joint angle.
Frames are generated lazily, when someone asks, up to the current simulated time.
"""

from __future__ import annotations

from collections import deque

import numpy as np

from amiro.activity.labels import IDLE
from amiro.activity.motion import FPS, Body, perform
from amiro.activity.skeleton import NUM_JOINTS, FloatArray, J
from amiro.sim.residents import Resident
from amiro.sim.simulator import Simulation

HISTORY_S = 4.0
# What an occluding object (the scenario's "skeleton occluded") leaves visible.
OCCLUSION_VISIBLE = tuple(J[n] for n in ("Head", "Neck", "SpineShoulder", "ShoulderLeft"))


class SkeletonStream:
    """One resident's body-frame skeletons, one per 1/FPS s of simulated time."""

    def __init__(self, body: Body, rng: np.random.Generator) -> None:
        self.body = body
        self.rng = rng
        self.frames: deque[FloatArray] = deque(maxlen=int(HISTORY_S * FPS))
        self.next_t: float | None = None
        self.pending: list[FloatArray] = []
        self.playing: tuple[str, bool] | None = None
        self.clips = 0  # clips generated since the activity or posture last changed

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
            self.frames.append(self.pending.pop(0))
            self.next_t += 1.0 / FPS

    def _clip(self, activity: str, sitting: bool) -> list[FloatArray]:
        if activity == "falling" and self.clips > 0:
            return [self.frames[-1]]  # after the fall: lying still
        action = IDLE if activity == "idle" else activity
        clip = list(perform(action, self.body, self.rng, FPS, sitting))
        if activity == "falling" and sitting:  # a seated person gets up, then falls
            return list(perform("standing_up", self.body, self.rng, FPS)) + clip
        return clip

    def last(self, n: int) -> FloatArray:
        frames = list(self.frames)[-n:]
        return np.stack([frames[0]] * (n - len(frames)) + frames)


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


class SkeletonCamera:
    """The skeleton source of the simulated robot (see :class:`SkeletonSource`)."""

    def __init__(self, sim: Simulation, rng: np.random.Generator) -> None:
        self.sim = sim
        self.rng = rng
        self.streams: dict[str, SkeletonStream] = {}

    def framing(self, person: str) -> tuple[float, bool] | None:
        obs = next((o for o in self.sim.observe() if o.name == person), None)
        if obs is None:
            return None
        height = float(self.sim.residents.camera.params.image_height)
        top = obs.bbox.cy - obs.bbox.height / 2.0
        bottom = obs.bbox.cy + obs.bbox.height / 2.0
        return obs.bbox.height / height, top <= 0.5 or bottom >= height - 0.5

    def window(self, person: str, frames: int) -> FloatArray | None:
        resident = self.sim.residents.residents.get(person)
        if resident is None or all(o.name != person for o in self.sim.observe()):
            return None
        stream = self.streams.get(person)
        if stream is None:
            stream = self.streams[person] = SkeletonStream(Body.random(self.rng), self.rng)
        sitting = resident.posture != "standing"
        stream.advance(self.sim.residents.now(), resident.activity, sitting)
        points = body_to_map(stream.last(frames), resident).reshape(-1, 3)
        robot, camera = self.sim.robot, self.sim.residents.camera
        pose, yaw = robot.true_pose, robot.head_yaw
        optical = camera.to_optical(points, pose, yaw, robot.head_pitch)
        uv = camera.project(optical)
        p = camera.params
        seen = (
            (optical[:, 2] > 0.1)
            & (uv[:, 0] >= 0)
            & (uv[:, 0] < p.width)
            & (uv[:, 1] >= 0)
            & (uv[:, 1] < p.image_height)
        )
        level = camera.to_optical(points, pose, yaw, 0.0) * np.array([-1.0, -1.0, 1.0])
        level[~seen] = np.nan
        out: FloatArray = level.reshape(frames, NUM_JOINTS, 3)
        if resident.skeleton_occluded:
            hidden = [j for j in range(NUM_JOINTS) if j not in OCCLUSION_VISIBLE]
            out[:, hidden] = np.nan
        return out
