"""Synthetic skeleton motion for the paper's eight actions and falling, from a parametric body.

A clip is one performance, like an NTU RGB+D sample: rest, the action, rest.  The body
(size, proportions, handedness) is a subject; the style (speed, amplitude, posture, head
and trunk) varies per clip.  Joints come from a small kinematic model: a trunk chain,
two-link arm and leg inverse kinematics towards time-varying targets.  Output is in the
body frame (x to the person's right, y up, z behind them, floor at y = 0), which is Kinect
camera space for a person facing the sensor; :func:`to_camera` places it in a view.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from amiro.activity.labels import ACTIONS, IDLE
from amiro.activity.skeleton import NUM_JOINTS, SEGMENT_LENGTH, FloatArray, J

FPS = 15.0  # model frame rate: NTU's 30 Hz taken every second frame

SITTING_SHARE = {
    "drink_water": 0.5,
    "hand_waving": 0.5,
    "play_phone": 0.6,
    "typing": 0.8,
    "pointing": 0.5,
    "sneeze_cough": 0.5,
    "touch_chest": 0.5,
    IDLE: 0.5,
}


@dataclass(frozen=True)
class Body:
    """A subject: segment lengths (m, per joint as in SEGMENT_LENGTH) and handedness."""

    lengths: FloatArray
    left_handed: bool

    @staticmethod
    def random(rng: np.random.Generator) -> Body:
        scale = rng.uniform(0.85, 1.12)
        jitter = rng.normal(1.0, 0.06, NUM_JOINTS).clip(0.85, 1.15)
        lengths = np.asarray(SEGMENT_LENGTH) * scale * jitter
        return Body(lengths, bool(rng.random() < 0.15))

    def length(self, joint: str) -> float:
        return float(self.lengths[J[joint]])


def smoothstep(x: FloatArray) -> FloatArray:
    x = np.clip(x, 0.0, 1.0)
    out: FloatArray = x * x * (3.0 - 2.0 * x)
    return out


def bump(t: FloatArray, start: float, rise: float, hold: float, fall: float) -> FloatArray:
    """0 -> 1 over ``rise`` seconds from ``start``, 1 for ``hold``, back to 0 over ``fall``."""
    up = smoothstep((t - start) / rise)
    down = smoothstep((t - start - rise - hold) / fall)
    out: FloatArray = up * (1.0 - down)
    return out


def _unit(v: FloatArray) -> FloatArray:
    out: FloatArray = v / np.maximum(np.linalg.norm(v, axis=-1, keepdims=True), 1e-9)
    return out


def two_link(
    root: FloatArray, target: FloatArray, upper: float, lower: float, pole: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Middle and end joints of a two-link chain reaching for ``target``, bent towards ``pole``."""
    d = target - root
    dist = np.clip(np.linalg.norm(d, axis=-1), abs(upper - lower) + 1e-3, upper + lower - 1e-3)
    u = _unit(d)
    v = _unit(pole - np.sum(pole * u, axis=-1, keepdims=True) * u)
    cos_a = (upper**2 + dist**2 - lower**2) / (2.0 * upper * dist)
    sin_a = np.sqrt(np.clip(1.0 - cos_a**2, 0.0, 1.0))
    mid = root + upper * (cos_a[:, None] * u + sin_a[:, None] * v)
    return mid, root + dist[:, None] * u


@dataclass
class Controls:
    """Time-varying inputs of the kinematic model, one row per frame."""

    pelvis: FloatArray  # (T, 3) SpineBase
    lean: FloatArray  # (T,) trunk pitch forward, rad
    roll: FloatArray  # (T,) trunk roll to the right, rad
    head_pitch: FloatArray  # (T,) head down relative to the trunk, rad
    ankles: tuple[FloatArray, FloatArray]  # (left, right) ankle targets
    wrists: tuple[FloatArray, FloatArray]  # (left, right) wrist targets, filled by anchors
    fingers: FloatArray  # (T, 3) hand-tip wiggle of both hands


class Pose:
    """The trunk of one clip and the anchor points arms reach for."""

    def __init__(self, body: Body, c: Controls) -> None:
        n = len(c.lean)
        self.body, self.c = body, c
        sl, cl = np.sin(c.lean), np.cos(c.lean)
        sr, cr = np.sin(c.roll), np.cos(c.roll)
        self.up = np.stack([sr * cl, cr * cl, -sl], axis=1)
        self.right = np.stack([cr, -sr, np.zeros(n)], axis=1)
        self.forward = np.cross(self.up, self.right)
        hp = c.lean + c.head_pitch
        self.head_up = np.stack([sr * np.cos(hp), cr * np.cos(hp), -np.sin(hp)], axis=1)
        b = body.length
        self.base = c.pelvis
        self.mid = self.base + b("SpineMid") * self.up
        self.spine_shoulder = self.mid + b("SpineShoulder") * self.up
        self.neck = self.spine_shoulder + b("Neck") * self.head_up
        self.head = self.neck + b("Head") * self.head_up

    def shoulder(self, side: int) -> FloatArray:
        """side +1: right, -1: left."""
        joint = "ShoulderRight" if side > 0 else "ShoulderLeft"
        out: FloatArray = self.spine_shoulder + side * self.body.length(joint) * self.right
        return out

    def hip(self, side: int) -> FloatArray:
        joint = "HipRight" if side > 0 else "HipLeft"
        out: FloatArray = self.base + side * self.body.length(joint) * self.right
        return out

    def anchor(self, name: str, side: int, sitting: bool) -> FloatArray:
        """Where a wrist goes for a named gesture, following the trunk."""
        r, up, fw = self.right, self.up, self.forward
        arm = self.body.length("ElbowRight") + self.body.length("WristRight")
        if name == "rest":
            if sitting:
                return self.hip(side) + 0.02 * side * r + 0.10 * up + 0.28 * fw
            return self.shoulder(side) + 0.07 * side * r - 0.95 * arm * up + 0.03 * fw
        if name == "mouth":
            return self.head - 0.10 * self.head_up + 0.10 * fw + 0.03 * side * r
        if name == "chest":
            return self.spine_shoulder - 0.12 * up + 0.12 * fw - 0.04 * side * r
        if name == "phone":
            return self.mid + 0.05 * up + 0.30 * fw + 0.07 * side * r
        if name == "keyboard":
            return self.base + 0.22 * up + 0.42 * fw + 0.13 * side * r
        if name == "wave":
            return self.shoulder(side) + 0.22 * side * r + 0.32 * up + 0.10 * fw
        raise ValueError(f"unknown anchor {name!r}")

    def joints(self) -> FloatArray:
        """All 25 joints, arms and legs solved towards the controls' targets."""
        b, c = self.body.length, self.c
        n = len(c.lean)
        out = np.empty((n, NUM_JOINTS, 3))
        out[:, J["SpineBase"]] = self.base
        out[:, J["SpineMid"]] = self.mid
        out[:, J["SpineShoulder"]] = self.spine_shoulder
        out[:, J["Neck"]] = self.neck
        out[:, J["Head"]] = self.head
        for side, tag in ((-1, "Left"), (1, "Right")):
            k = 0 if side < 0 else 1
            sh = self.shoulder(side)
            pole = side * 0.8 * self.right - self.up - 0.3 * self.forward
            elbow, wrist = two_link(
                sh, c.wrists[k], b("Elbow" + tag), b("Wrist" + tag), np.broadcast_to(pole, sh.shape)
            )
            along = _unit(wrist - elbow)
            hand = wrist + b("Hand" + tag) * along
            out[:, J["Shoulder" + tag]] = sh
            out[:, J["Elbow" + tag]] = elbow
            out[:, J["Wrist" + tag]] = wrist
            out[:, J["Hand" + tag]] = hand
            out[:, J["HandTip" + tag]] = hand + b("HandTip" + tag) * _unit(along + c.fingers)
            thumb_dir = _unit(along - 0.8 * side * self.right + 0.3 * self.up)
            out[:, J["Thumb" + tag]] = wrist + b("Thumb" + tag) * thumb_dir
            hip = self.hip(side)
            knee_pole = np.broadcast_to(np.array([0.15 * side, 0.3, -1.0]), hip.shape)
            knee, ankle = two_link(hip, c.ankles[k], b("Knee" + tag), b("Ankle" + tag), knee_pole)
            out[:, J["Hip" + tag]] = hip
            out[:, J["Knee" + tag]] = knee
            out[:, J["Ankle" + tag]] = ankle
            out[:, J["Foot" + tag]] = ankle + b("Foot" + tag) * np.array([0.0, -0.35, -0.94])
        return out


@dataclass(frozen=True)
class Stance:
    """Where pelvis and ankles are when sitting or standing, for one body."""

    sit_pelvis: FloatArray
    stand_pelvis: FloatArray
    sit_ankles: tuple[FloatArray, FloatArray]
    stand_ankles: tuple[FloatArray, FloatArray]

    @staticmethod
    def of(body: Body, rng: np.random.Generator) -> Stance:
        leg = body.length("KneeRight") + body.length("AnkleRight")
        hip = body.length("HipRight")
        seat = rng.uniform(0.40, 0.50) * leg / 0.75
        feet_fw = rng.uniform(0.35, 0.5)
        return Stance(
            np.array([0.0, seat + 0.06, 0.0]),
            np.array([0.0, 0.97 * leg + 0.08, -feet_fw + 0.04]),
            (np.array([-hip * 1.2, 0.08, -feet_fw]), np.array([hip * 1.2, 0.08, -feet_fw])),
            (np.array([-hip * 1.1, 0.08, -feet_fw]), np.array([hip * 1.1, 0.08, -feet_fw])),
        )


class Clip:
    """Builds one clip: a time base, default controls for a posture, then the action."""

    def __init__(
        self, body: Body, rng: np.random.Generator, duration: float, length: float, fps: float
    ) -> None:
        self.body, self.rng = body, rng
        self.length = length  # of the action itself, in the subject's own time
        self.t = np.arange(round(duration * fps)) / fps
        self.stance = Stance.of(body, rng)
        self.dominant = -1 if body.left_handed else 1

    def const(self, value: float) -> FloatArray:
        return np.full(len(self.t), value)

    def controls(self, sitting: bool) -> Controls:
        s = self.stance
        n = len(self.t)
        pelvis = np.tile(s.sit_pelvis if sitting else s.stand_pelvis, (n, 1))
        ankles = s.sit_ankles if sitting else s.stand_ankles
        breathe = 0.02 * np.sin(2 * np.pi * 0.25 * self.t + self.rng.uniform(0, 6.3))
        return Controls(
            pelvis=pelvis,
            lean=breathe + self.rng.uniform(-0.05, 0.15),
            roll=self.const(self.rng.normal(0.0, 0.03)),
            head_pitch=self.const(self.rng.normal(0.05, 0.08)),
            ankles=(np.tile(ankles[0], (n, 1)), np.tile(ankles[1], (n, 1))),
            wrists=(np.zeros((n, 3)), np.zeros((n, 3))),
            fingers=np.zeros((n, 3)),
        )


def _reach(
    pose: Pose, side: int, sitting: bool, goal: str, weight: FloatArray, extra: FloatArray | None
) -> FloatArray:
    rest = pose.anchor("rest", side, sitting)
    target = rest + weight[:, None] * (pose.anchor(goal, side, sitting) - rest)
    return target if extra is None else target + extra


def perform(
    action: str,
    body: Body,
    rng: np.random.Generator,
    fps: float = FPS,
    sitting: bool | None = None,
) -> FloatArray:
    """One clip of ``action`` (or :data:`IDLE`) in the body frame: ``(frames, 25, 3)``."""
    if action not in (*ACTIONS, IDLE):
        raise ValueError(f"unknown action {action!r}")
    speed = rng.uniform(0.75, 1.3)
    pre, post = rng.uniform(0.2, 0.8, 2)
    if action == "standing_up":
        sitting = True
    elif action == "falling":
        sitting = False
    elif sitting is None:
        sitting = bool(rng.random() < SITTING_SHARE[action])
    plan = _PLANS[action]()
    length = plan.duration(rng)
    clip = Clip(body, rng, pre + length / speed + post, length, fps)
    ctl = clip.controls(sitting)
    tau = (clip.t - pre) * speed  # action time at the subject's own pace
    plan.shape(clip, ctl, tau, sitting)
    pose = Pose(body, ctl)
    weights, goals, extras = plan.arms(clip, pose, tau, sitting)
    ctl.wrists = tuple(  # type: ignore[assignment]
        _reach(pose, side, sitting, goals[k], weights[k], extras[k])
        for k, side in enumerate((-1, 1))
    )
    joints = pose.joints()
    return plan.finish(clip, joints, tau)


class Plan:
    """How an action drives the controls; subclasses override the parts they change."""

    span: tuple[float, float] = (2.0, 3.0)

    def duration(self, rng: np.random.Generator) -> float:
        return float(rng.uniform(*self.span))

    def shape(self, clip: Clip, ctl: Controls, tau: FloatArray, sitting: bool) -> None:
        """Trunk, head and pelvis over time."""

    def arms(
        self, clip: Clip, pose: Pose, tau: FloatArray, sitting: bool
    ) -> tuple[list[FloatArray], list[str], list[FloatArray | None]]:
        """(weight towards the goal, goal anchor, extra offset) for the left and right wrist."""
        zero = np.zeros_like(tau)
        return [zero, zero], ["rest", "rest"], [None, None]

    def finish(self, clip: Clip, joints: FloatArray, tau: FloatArray) -> FloatArray:
        return joints


def _dominant_only(
    clip: Clip, goal: str, weight: FloatArray, extra: FloatArray | None = None
) -> tuple[list[FloatArray], list[str], list[FloatArray | None]]:
    k = 0 if clip.dominant < 0 else 1
    weights = [np.zeros_like(weight), np.zeros_like(weight)]
    goals = ["rest", "rest"]
    extras: list[FloatArray | None] = [None, None]
    weights[k], goals[k], extras[k] = weight, goal, extra
    return weights, goals, extras


class Idle(Plan):
    span = (2.5, 4.0)


class Drink(Plan):
    """Bring the cup to the mouth (0.6-0.9 s), hold it there while the head tilts back
    and the cup tips up, and put it down: slow, with a long still hold."""

    def duration(self, rng: np.random.Generator) -> float:
        self.rise = float(rng.uniform(0.6, 0.9))
        self.hold = float(rng.uniform(1.0, 2.2))
        self.fall = float(rng.uniform(0.6, 0.8))
        self.tilt = float(rng.uniform(0.3, 0.5))
        return self.rise + self.hold + self.fall

    def _tipping(self, tau: FloatArray) -> FloatArray:
        return bump(tau, self.rise - 0.1, 0.4, self.hold - 0.3, 0.4)

    def shape(self, clip: Clip, ctl: Controls, tau: FloatArray, sitting: bool) -> None:
        tipping = self._tipping(tau)
        ctl.head_pitch = ctl.head_pitch - self.tilt * tipping
        ctl.lean = ctl.lean - 0.4 * self.tilt * tipping

    def arms(
        self, clip: Clip, pose: Pose, tau: FloatArray, sitting: bool
    ) -> tuple[list[FloatArray], list[str], list[FloatArray | None]]:
        weight = bump(tau, 0.0, self.rise, self.hold, self.fall)
        tip = (self.tilt * self._tipping(tau))[:, None] * (0.15 * pose.up + 0.1 * pose.forward)
        return _dominant_only(clip, "mouth", weight, tip)


class Sneeze(Plan):
    """Hand(s) snap to the face (0.15-0.3 s), then one big forward jerk of head and trunk
    (a sneeze) or two or three smaller ones (a cough), and the hand(s) drop soon after."""

    def duration(self, rng: np.random.Generator) -> float:
        self.rise = float(rng.uniform(0.15, 0.3))
        cough = bool(rng.random() < 0.5)
        if cough:  # (time to the next jerk, trunk pitch of this one)
            count = int(rng.integers(2, 4))
            self.jerks = [(rng.uniform(0.35, 0.5), rng.uniform(0.15, 0.3)) for _ in range(count)]
        else:
            self.jerks = [(0.45, rng.uniform(0.35, 0.55))]
        self.both = bool(rng.random() < (0.2 if cough else 0.5))
        self.fall = float(rng.uniform(0.35, 0.5))
        return self.rise + sum(gap for gap, _ in self.jerks) + 0.2 + self.fall

    def shape(self, clip: Clip, ctl: Controls, tau: FloatArray, sitting: bool) -> None:
        at = self.rise + 0.05
        for gap, size in self.jerks:
            jerk = bump(tau, at, 0.1, 0.05, 0.3)
            ctl.lean = ctl.lean + size * jerk
            ctl.head_pitch = ctl.head_pitch + 1.2 * size * jerk
            at += gap

    def arms(
        self, clip: Clip, pose: Pose, tau: FloatArray, sitting: bool
    ) -> tuple[list[FloatArray], list[str], list[FloatArray | None]]:
        hold = sum(gap for gap, _ in self.jerks) + 0.2
        w = bump(tau, 0.0, self.rise, hold, self.fall)
        cover = (0.05 * w)[:, None] * pose.forward  # a hand in front of the face, not on it
        if self.both:
            return [w, w], ["mouth", "mouth"], [cover, cover]
        return _dominant_only(clip, "mouth", w, cover)


class TouchChest(Plan):
    span = (2.6, 3.8)

    def shape(self, clip: Clip, ctl: Controls, tau: FloatArray, sitting: bool) -> None:
        w = bump(tau, 0.3, 0.5, clip.length - 1.6, 0.5)
        ctl.lean = ctl.lean + 0.1 * w
        ctl.head_pitch = ctl.head_pitch + 0.15 * w

    def arms(
        self, clip: Clip, pose: Pose, tau: FloatArray, sitting: bool
    ) -> tuple[list[FloatArray], list[str], list[FloatArray | None]]:
        w = bump(tau, 0.0, 0.7, clip.length - 1.4, 0.7)
        phase = 2 * np.pi * 1.5 * tau
        rub = 0.02 * np.stack([np.cos(phase), np.sin(phase), np.zeros_like(tau)], axis=1)
        return _dominant_only(clip, "chest", w, rub * w[:, None])


class Pointing(Plan):
    span = (2.2, 3.2)

    def arms(
        self, clip: Clip, pose: Pose, tau: FloatArray, sitting: bool
    ) -> tuple[list[FloatArray], list[str], list[FloatArray | None]]:
        side = clip.dominant
        az = clip.rng.uniform(-0.3, 0.7) * side
        el = clip.rng.uniform(-0.15, 0.45)
        reach = 0.97 * (clip.body.length("ElbowRight") + clip.body.length("WristRight"))
        direction = np.cos(el) * (np.cos(az) * pose.forward + np.sin(az) * pose.right)
        direction = direction + np.sin(el) * pose.up
        w = bump(tau, 0.0, 0.6, clip.length - 1.2, 0.6)
        shoulder = pose.shoulder(side)
        rest = pose.anchor("rest", side, sitting)
        extra = w[:, None] * (shoulder + reach * direction - rest)
        return _dominant_only(clip, "rest", np.zeros_like(tau), extra)


class Waving(Plan):
    span = (2.4, 3.6)

    def arms(
        self, clip: Clip, pose: Pose, tau: FloatArray, sitting: bool
    ) -> tuple[list[FloatArray], list[str], list[FloatArray | None]]:
        freq = clip.rng.uniform(1.5, 2.6)
        amp = clip.rng.uniform(0.10, 0.2)
        w = bump(tau, 0.0, 0.5, clip.length - 1.0, 0.5)
        swing = amp * np.sin(2 * np.pi * freq * tau)[:, None] * pose.right
        return _dominant_only(clip, "wave", w, swing * w[:, None])


class Phone(Plan):
    span = (3.0, 4.0)

    def shape(self, clip: Clip, ctl: Controls, tau: FloatArray, sitting: bool) -> None:
        ctl.head_pitch = ctl.head_pitch + clip.rng.uniform(0.3, 0.55) * smoothstep(tau / 0.6)
        ctl.fingers = 0.25 * np.sin(2 * np.pi * 3.0 * tau)[:, None] * np.array([0.0, 1.0, 0.0])

    def arms(
        self, clip: Clip, pose: Pose, tau: FloatArray, sitting: bool
    ) -> tuple[list[FloatArray], list[str], list[FloatArray | None]]:
        w = smoothstep(tau / 0.6)
        if clip.rng.random() < 0.8:
            return [w, w], ["phone", "phone"], [None, None]
        return _dominant_only(clip, "phone", w)


class Typing(Plan):
    span = (3.0, 4.0)

    def shape(self, clip: Clip, ctl: Controls, tau: FloatArray, sitting: bool) -> None:
        ctl.head_pitch = ctl.head_pitch + clip.rng.uniform(0.12, 0.3) * smoothstep(tau / 0.5)
        ctl.lean = ctl.lean + clip.rng.uniform(0.05, 0.2) * smoothstep(tau / 0.5)

    def arms(
        self, clip: Clip, pose: Pose, tau: FloatArray, sitting: bool
    ) -> tuple[list[FloatArray], list[str], list[FloatArray | None]]:
        w = smoothstep(tau / 0.5)
        freq = clip.rng.uniform(4.0, 6.0)
        taps = [
            0.015 * np.sin(2 * np.pi * freq * tau + clip.rng.uniform(0, 6.3))[:, None] * pose.up
            for _ in range(2)
        ]
        return [w, w], ["keyboard", "keyboard"], [taps[0] * w[:, None], taps[1] * w[:, None]]


class StandUp(Plan):
    span = (1.8, 2.6)

    def shape(self, clip: Clip, ctl: Controls, tau: FloatArray, sitting: bool) -> None:
        s = clip.stance
        rise = smoothstep((tau - 0.5) / 1.0)
        ctl.pelvis = s.sit_pelvis + rise[:, None] * (s.stand_pelvis - s.sit_pelvis)
        ctl.lean = ctl.lean + 0.55 * bump(tau, 0.0, 0.5, 0.4, 0.7)
        ctl.ankles = tuple(  # type: ignore[assignment]
            sit + rise[:, None] * (stand - sit)
            for sit, stand in zip(s.sit_ankles, s.stand_ankles, strict=True)
        )
        self.rise = rise

    def arms(
        self, clip: Clip, pose: Pose, tau: FloatArray, sitting: bool
    ) -> tuple[list[FloatArray], list[str], list[FloatArray | None]]:
        extras: list[FloatArray | None] = []
        for side in (-1, 1):
            seated = pose.anchor("rest", side, True)
            upright = pose.anchor("rest", side, False)
            extras.append(self.rise[:, None] * (upright - seated))
        zero = np.zeros_like(tau)
        return [zero, zero], ["rest", "rest"], extras


class Fall(Plan):
    span = (2.0, 2.8)

    def shape(self, clip: Clip, ctl: Controls, tau: FloatArray, sitting: bool) -> None:
        buckle = smoothstep(tau / 0.4)
        ctl.pelvis = ctl.pelvis - 0.25 * buckle[:, None] * np.array([0.0, 1.0, 0.0])
        self.topple = smoothstep((tau - 0.3) / clip.rng.uniform(0.6, 0.9))
        self.angle = clip.rng.uniform(1.3, 1.55)
        self.heading = clip.rng.uniform(-np.pi, np.pi)

    def arms(
        self, clip: Clip, pose: Pose, tau: FloatArray, sitting: bool
    ) -> tuple[list[FloatArray], list[str], list[FloatArray | None]]:
        w = smoothstep((tau - 0.2) / 0.5)
        extras: list[FloatArray | None] = []
        for side in (-1, 1):
            out = 0.25 * side * pose.right + 0.35 * pose.forward + 0.25 * pose.up
            extras.append(w[:, None] * out)
        zero = np.zeros_like(tau)
        return [zero, zero], ["rest", "rest"], extras

    def finish(self, clip: Clip, joints: FloatArray, tau: FloatArray) -> FloatArray:
        """Topple the whole body about the ankles, towards a random direction."""
        ankles = joints[:, [J["AnkleLeft"], J["AnkleRight"]]].mean(axis=1)
        pivot = ankles * np.array([1.0, 0.0, 1.0])
        axis = np.array([np.cos(self.heading), 0.0, np.sin(self.heading)])
        out = np.empty_like(joints)
        for i, a in enumerate(self.angle * self.topple):
            rot = _rotation(axis, float(a))
            out[i] = (joints[i] - pivot[i]) @ rot.T + pivot[i]
        out[..., 1] = np.maximum(out[..., 1], 0.03)
        return out


def _rotation(axis: FloatArray, angle: float) -> FloatArray:
    """Rodrigues' rotation matrix."""
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    out: FloatArray = np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * (k @ k)
    return out


_PLANS: dict[str, type[Plan]] = {
    "drink_water": Drink,
    "standing_up": StandUp,
    "hand_waving": Waving,
    "play_phone": Phone,
    "typing": Typing,
    "pointing": Pointing,
    "sneeze_cough": Sneeze,
    "touch_chest": TouchChest,
    "falling": Fall,
    IDLE: Idle,
}


@dataclass(frozen=True)
class View:
    """Where the sensor stands: the body's yaw to it, distance, height and pitch."""

    yaw: float = 0.0
    distance: float = 3.0
    height: float = 1.0
    pitch: float = 0.0


def to_camera(body_frames: FloatArray, view: View) -> FloatArray:
    """Body-frame joints into Kinect camera space for a sensor at ``view``."""
    c, s = np.cos(view.yaw), np.sin(view.yaw)
    turn = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
    cp, sp = np.cos(view.pitch), np.sin(view.pitch)
    tilt = np.array([[1.0, 0.0, 0.0], [0.0, cp, -sp], [0.0, sp, cp]])
    placed = body_frames @ turn.T + np.array([0.0, -view.height, view.distance])
    out: FloatArray = placed @ tilt.T
    return out


def sensor_noise(frames: FloatArray, rng: np.random.Generator, sigma: float = 0.01) -> FloatArray:
    """Kinect-like jitter: isotropic plus depth noise growing with distance squared."""
    noisy = frames + rng.normal(0.0, sigma, frames.shape)
    noisy[..., 2] += rng.normal(0.0, 1.0, frames.shape[:-1]) * 1.5e-3 * frames[..., 2] ** 2
    out: FloatArray = noisy
    return out
