"""The activity recognisers ``activity.backend`` names (see :mod:`amiro.core.registry`).

Kind ``activity``: ``factory(inputs: ActivityInputs) -> ActivityRecognizer``
(:class:`amiro.activity.stack.ActivityInputs`); ``inputs`` carries the simulator's head
camera and skeleton stream, or a real robot's camera for a pose model, and a factory refuses
the one it cannot read.

Only names and import paths here: the config module imports this before any model loads.
"""

from __future__ import annotations

from amiro.core.registry import register

register("activity", "onnx", "amiro.activity.stack:onnx_recognizer")
register("activity", "oracle", "amiro.sim.activity_oracle:oracle_recognizer")
register("activity", "camera-onnx", "amiro.activity.stack:camera_onnx_recognizer", extra="vision")
register(
    "activity",
    "camera-mediapipe",
    "amiro.activity.stack:camera_mediapipe_recognizer",
    extra="pose",
)
