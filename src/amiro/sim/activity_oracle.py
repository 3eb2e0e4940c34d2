"""Oracle activity recognition for the simulator: the resident's true activity, with errors.

A bootstrap and test backend, named as such.  It sees nothing when the person is out of
view or their skeleton is occluded, and mislabels with probability ``1 - accuracy``.
"""

from __future__ import annotations

import numpy as np

from amiro.activity.ports import ActivityReading, ActivityRecognizer
from amiro.activity.stack import ActivityInputs
from amiro.robot.camera import HeadCamera
from amiro.sim.residents import ACTIVITIES


class OracleActivityRecognizer:
    box_range: tuple[float, float] | None = None  # the oracle sees as well from anywhere

    def __init__(self, sim: HeadCamera, rng: np.random.Generator, accuracy: float = 0.95) -> None:
        self.sim = sim
        self.rng = rng
        self.accuracy = accuracy

    def observe(self, person: str) -> ActivityReading:
        obs = next((o for o in self.sim.observe() if o.name == person), None)
        if obs is None or obs.skeleton_occluded:
            return ActivityReading(None, 0.0, False)
        label = obs.activity
        if self.rng.random() > self.accuracy:
            others = [a for a in ACTIVITIES if a != label]
            label = others[int(self.rng.integers(len(others)))]
        return ActivityReading(label, float(self.accuracy), True)


def oracle_recognizer(inputs: ActivityInputs) -> ActivityRecognizer:
    """The ``oracle`` activity backend (registered in :mod:`amiro.activity.backends`)."""

    camera, _ = inputs.simulated()
    return OracleActivityRecognizer(camera, inputs.rng, inputs.cfg.accuracy)
