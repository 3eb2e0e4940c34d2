"""The simulator's face recogniser: who the camera model sees, with the paper's failures.

Recognition needs the face towards the camera, gets less reliable with distance, seldom
confuses two residents, and fails when the camera faces a light source behind the person
(the paper's section-5 observation).  Anyone not enrolled is "unknown", never a guess.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np

from amiro.perception.config import FaceSection
from amiro.robot.camera import CameraObservation


class SimFaceIdentifier:
    def __init__(
        self, rng: np.random.Generator, enrolled: Iterable[str], cfg: FaceSection | None = None
    ) -> None:
        self.rng = rng
        self.enrolled = sorted(set(enrolled))
        self.cfg = cfg or FaceSection()

    def success_rate(self, obs: CameraObservation) -> float:
        if not obs.face_visible:
            return 0.0
        if obs.backlit:
            return self.cfg.backlit_rate
        rate = self.cfg.recognise_rate - self.cfg.rate_loss_per_m * max(obs.depth - 1.0, 0.0)
        return float(np.clip(rate, 0.0, 1.0))

    def identify(self, obs: CameraObservation) -> str | None:
        """The person's name, another resident's (rarely), or None for unknown."""
        if not obs.face_visible:
            return None
        draw = float(self.rng.random())
        rate = self.success_rate(obs)
        if draw < rate:
            return obs.name if obs.name in self.enrolled else None
        others = [n for n in self.enrolled if n != obs.name]
        if others and draw < rate + self.cfg.confusion_rate:
            return others[int(self.rng.integers(len(others)))]
        return None
