"""What perception and activity read from the robot's head, wherever the robot runs.

The in-process :class:`~amiro.sim.simulator.Simulation` offers it directly; split over ROS 2,
the edge offers the same from bridged topics (:mod:`amiro.ros2.boundary`), so both run the
same perception and activity code.

The simulated camera renders no pixels: its frame is the list of
:class:`~amiro.sim.messages.CameraObservation`.  Of their ground-truth fields only those the
simulated detector (box, depth, posture) and face backend (name, face towards the camera,
backlight) model are read by the real modules; the rest is for the oracles and scoring.
"""

from __future__ import annotations

from typing import Protocol

from amiro.core.messages import CameraInfo, Pose2D
from amiro.sim.messages import CameraObservation


class HeadCamera(Protocol):
    def now(self) -> float:
        """The time of the current frame (s)."""
        ...

    def observe(self) -> list[CameraObservation]:
        """The current frame: everyone the head camera sees."""
        ...

    def head_joints(self) -> tuple[float, float] | None:
        """(HeadYaw, HeadPitch) when the frame was taken; None before any joint state."""
        ...

    def camera_info(self) -> CameraInfo | None:
        """The RGB image's intrinsics; None before the camera has reported them."""
        ...

    def camera_mount(self) -> tuple[float, float]:
        """Where the camera sits: height above the floor and ahead of the base centre (m)."""
        ...

    def robot_pose(self) -> Pose2D | None:
        """A pose the source itself knows: the simulator's ground truth in one process (for
        evaluations without localisation), None from a bus feed."""
        ...

    def household(self) -> tuple[str, ...]:
        """The residents' names: the face gallery's enrolled people."""
        ...
