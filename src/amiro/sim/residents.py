"""Simulated residents: where they are, what they do and how they answer the robot.

Each resident follows a reply script per prompt kind (a list is consumed in order, its last
entry then repeats), so scenarios such as "postpone once, then confirm" are declarative and
repeatable; the wording is drawn from the phrase tables with the caller's seeded generator.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
import numpy.typing as npt

from amiro.activity.labels import ACTIONS, IDLE
from amiro.core.messages import Point
from amiro.home.household import LANGUAGES
from amiro.sim.phrases import INTENTS, PHRASES, context_of

Posture = Literal["standing", "sitting_desk", "sitting_couch", "lying_couch"]
ReplyKind = Literal["confirm", "deny", "postpone", "silence"]

POSTURES: tuple[str, ...] = ("standing", "sitting_desk", "sitting_couch", "lying_couch")
ACTIVITIES: tuple[str, ...] = (*ACTIONS, IDLE)
PROMPT_KINDS: tuple[str, ...] = (
    "hydration_reminder",
    "postpone_question",
    "activity_confirmation",
    "default",
)
DRINK_DURATION = 8.0  # s of drink_water after confirming a hydration reminder


@dataclass(frozen=True, slots=True)
class BodyBox:
    """The person's body as an upright box: z range, width across, length along heading."""

    z_min: float
    z_max: float
    width: float
    length: float

    @property
    def torso_z(self) -> float:
        return 0.5 * (self.z_min + self.z_max)


BODY_BOXES: dict[str, BodyBox] = {
    "standing": BodyBox(0.0, 1.70, 0.5, 0.3),
    "sitting_desk": BodyBox(0.0, 1.25, 0.5, 0.5),
    "sitting_couch": BodyBox(0.0, 1.25, 0.5, 0.5),
    "lying_couch": BodyBox(0.35, 0.90, 0.5, 1.8),
}


@dataclass(frozen=True, slots=True)
class ScriptedReply:
    reply: ReplyKind = "confirm"
    delay: float = 2.0  # s after the robot spoke


@dataclass(frozen=True, slots=True)
class Reply:
    """A resident's answer: text in their language and the ground-truth intent."""

    resident: str
    prompt: str
    reply: ReplyKind
    text: str
    lang: str
    intent: str
    delay: float


@dataclass
class Resident:
    name: str
    x: float
    y: float
    heading: float = 0.0
    language: str = "en"
    posture: Posture = "standing"
    activity: str = "idle"
    present: bool = True
    skeleton_occluded: bool = False
    script: dict[str, list[ScriptedReply]] = field(default_factory=dict)
    activity_until: float | None = None
    _asked: dict[str, int] = field(default_factory=dict, repr=False)

    def __post_init__(self) -> None:
        if self.language not in LANGUAGES:
            raise ValueError(f"resident {self.name}: unsupported language {self.language!r}")
        if self.posture not in POSTURES:
            raise ValueError(f"resident {self.name}: unknown posture {self.posture!r}")
        if self.activity not in ACTIVITIES:
            raise ValueError(f"resident {self.name}: unknown activity {self.activity!r}")

    # --- body ---------------------------------------------------------------------------
    @property
    def body(self) -> BodyBox:
        return BODY_BOXES[self.posture]

    def torso(self) -> Point:
        """True torso centre in the map frame."""
        return Point(self.x, self.y, self.body.torso_z)

    def distance_to(self, x: float, y: float) -> float:
        return math.hypot(self.x - x, self.y - y)

    def body_corners(self) -> npt.NDArray[np.float64]:
        """The 8 corners (x, y, z) of the body box in the map frame."""
        b = self.body
        c, s = math.cos(self.heading), math.sin(self.heading)
        along = np.array([-0.5, 0.5, 0.5, -0.5]) * b.length
        across = np.array([-0.5, -0.5, 0.5, 0.5]) * b.width
        xs = self.x + c * along - s * across
        ys = self.y + s * along + c * across
        return np.array(
            [[x, y, z] for z in (b.z_min, b.z_max) for x, y in zip(xs, ys, strict=True)]
        )

    # --- activity -----------------------------------------------------------------------
    def start_activity(self, activity: str, now: float, duration: float | None = None) -> None:
        if activity not in ACTIVITIES:
            raise ValueError(f"unknown activity {activity!r}")
        self.activity = activity
        self.activity_until = None if duration is None else now + duration

    def update(self, now: float) -> bool:
        """End a timed activity; returns True when the activity changed."""
        if self.activity_until is not None and now >= self.activity_until:
            self.activity = "idle"
            self.activity_until = None
            return True
        return False

    # --- dialogue -----------------------------------------------------------------------
    def scripted(self, prompt: str) -> ScriptedReply:
        """The scripted reply to the next prompt of this kind (advances the script)."""
        key = prompt if prompt in self.script else "default"
        seq = self.script.get(key)
        if not seq:
            return ScriptedReply()
        i = self._asked.get(key, 0)
        self._asked[key] = i + 1
        return seq[min(i, len(seq) - 1)]

    def reply_to(self, prompt: str, rng: np.random.Generator) -> Reply | None:
        """Answer a prompt per the script; None for silence (the robot hears nothing)."""
        step = self.scripted(prompt)
        if step.reply == "silence":
            return None
        variants = PHRASES[self.language][context_of(prompt)][step.reply]
        text = variants[int(rng.integers(len(variants)))]
        return Reply(
            self.name, prompt, step.reply, text, self.language, INTENTS[step.reply], step.delay
        )
