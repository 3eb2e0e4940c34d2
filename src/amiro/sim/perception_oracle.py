"""Oracle perception for the simulator: the camera model's ground truth plus noise.

A bootstrap and test backend, named as such: it knows who is in view from the simulator
rather than from images.  The identity is given only when the face is towards the camera,
and positions get Gaussian noise, so behaviours meet some of the real module's trouble.
"""

from __future__ import annotations

import numpy as np

from amiro.core.messages import Point
from amiro.perception.ports import PeopleFinder, SeenPerson
from amiro.perception.stack import PerceptionInputs
from amiro.robot.camera import HeadCamera


class OraclePeopleFinder:
    def __init__(
        self, sim: HeadCamera, rng: np.random.Generator, position_noise_m: float = 0.1
    ) -> None:
        self.sim = sim
        self.rng = rng
        self.noise = position_noise_m

    def look(self) -> list[SeenPerson]:
        seen = []
        for obs in self.sim.observe():
            dx, dy = self.rng.normal(0.0, self.noise, 2) if self.noise > 0 else (0.0, 0.0)
            position = Point(obs.position.x + float(dx), obs.position.y + float(dy), obs.position.z)
            name = obs.name if obs.face_visible else None
            seen.append(SeenPerson(name, position, 0.9 if name else 0.6))
        return seen


def oracle_people_finder(inputs: PerceptionInputs) -> PeopleFinder:
    """The ``oracle`` perception backend (registered in :mod:`amiro.perception.backends`)."""
    return OraclePeopleFinder(inputs.simulated_head(), inputs.rng, inputs.cfg.position_noise_m)
