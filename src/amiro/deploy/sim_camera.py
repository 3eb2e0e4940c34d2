"""The simulated robot's head camera as pixels, for ``amiro sim --ros2``.

A real robot's driver publishes RGB, depth and CameraInfo; so does the simulator here, at a
low rate and size (rendering and HOG cost CPU), so that the real-robot path (``robot.adapter:
ros2``, ``perception.backend: camera``) can be exercised end to end against it.  Each present
resident in the camera's line of sight is ray-cast as an upright cylinder as tall as their
posture's body and drawn as a human silhouette (what OpenCV's HOG detector needs), with
:mod:`amiro.perception.synthetic_scene`; walls and furniture are not drawn.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from amiro.core import names
from amiro.core.messages import CameraInfo, Header, Image
from amiro.core.node import Node
from amiro.deploy.config import SimCameraSection
from amiro.perception.synthetic_scene import Cylinder, Scene, render
from amiro.robot.camera import Camera
from amiro.sim.simulator import Simulation


class SimCameraNode(Node):
    """Publishes rendered ``rgb8`` images, ``32FC1`` depth (m) and the matching CameraInfo on
    the robot port's camera topics, from the simulator's true robot pose and head joints."""

    def __init__(self, sim: Simulation, cfg: SimCameraSection, name: str = "sim_camera") -> None:
        super().__init__(name)
        self.sim = sim
        params = replace(sim.residents.camera.params, width=cfg.width, image_height=cfg.height)
        self.camera = Camera(params)  # the simulator's optics at the rendered size
        self.period = 1.0 / cfg.rate_hz
        self.frames = 0

    def on_start(self) -> None:
        self.pub_rgb = self.create_publisher(names.IMAGE, Image)
        self.pub_depth = self.create_publisher(names.DEPTH, Image)
        self.pub_info = self.create_publisher(names.CAMERA_INFO, CameraInfo)
        self.create_timer(self.period, self.publish)

    def people_in_sight(self) -> list[Cylinder]:
        """Present residents the walls do not hide from the camera, as cylinders."""
        robot = self.sim.robot_pose()
        yaw, _ = self.sim.head_joints()
        cx, cy, _ = self.camera.position(robot, yaw)
        world = self.sim.world
        return [
            Cylinder(r.x, r.y, height=r.body.z_max)
            for r in self.sim.residents.residents.values()
            if r.present and world.line_of_sight((cx, cy), (r.x, r.y), r.body.z_max)
        ]

    def frame(self) -> Scene:
        yaw, pitch = self.sim.head_joints()
        people = self.people_in_sight()
        return render(self.camera, self.sim.robot_pose(), people, yaw, pitch, drawn=True)

    def publish(self) -> None:
        scene = self.frame()
        now = self.now()
        header = Header(now, self.camera.params.frame_id)
        h, w = scene.depth.shape
        self.pub_rgb.publish(Image(header, h, w, "rgb8", scene.rgb))
        self.pub_depth.publish(Image(header, h, w, "32FC1", scene.depth.astype(np.float32)))
        self.pub_info.publish(self.camera.info(now))
        self.frames += 1
