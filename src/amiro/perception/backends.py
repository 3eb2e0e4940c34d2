"""The backends perception is configured with, by name (see :mod:`amiro.core.registry`).

Each kind, the config field that names it, and how its factory is called:

- ``perception`` (``perception.backend``): ``factory(inputs: PerceptionInputs) ->
  PeopleFinder``; ``inputs`` carries the simulator's head camera or a real robot's camera
  feed, and a factory refuses the one it cannot read (on a camera it must return a
  :class:`~amiro.perception.camera_finder.CameraPeopleFinder`, whose boxes the activity
  module's pose model shares).
  ``hri`` reads the persons another HRI stack publishes on ROS4HRI, which a ROS 2
  deployment's edge puts on the bus (``inputs.bus``, topic ``/amiro/hri/people``).
- ``faces`` (``perception.faces.backend``): ``factory(cfg: PerceptionConfig) -> FaceGallery |
  None``, what names the people in a camera's images (None: tracked unnamed).  The simulated
  people finder runs the simulator's own face model and accepts only ``sim``.
- ``detector`` (``perception.camera.detector``): ``factory(cfg: CameraSection) -> Detector``.

Only names and import paths here: the config module imports this before any model loads.
"""

from __future__ import annotations

from amiro.core.registry import register

register("perception", "sim", "amiro.perception.stack:sim_people_finder")
register("perception", "oracle", "amiro.sim.perception_oracle:oracle_people_finder")
register("perception", "camera", "amiro.system.camera:camera_people_finder", extra="vision")
register("perception", "hri", "amiro.perception.hri:hri_people_finder", extra="ros2")
register("faces", "sim", "amiro.system.camera:unnamed_faces")
register("faces", "dlib", "amiro.system.camera:dlib_faces", extra="faces")
register("detector", "hog", "amiro.system.camera:hog_detector", extra="vision")
register("detector", "onnx", "amiro.system.camera:onnx_detector", extra="vision")
