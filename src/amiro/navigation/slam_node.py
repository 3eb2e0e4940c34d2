"""Hector-style SLAM on the bus: ``/scan`` + ``/odom`` in, the robot's estimated pose out.

The paper records its navigation experiments with the pose computed by SLAM; this node gives
the same estimate online and keeps the trajectory (sim time, pose) for scoring.
"""

from __future__ import annotations

from amiro.core import names
from amiro.core.messages import LaserScan, Odometry, Pose2D
from amiro.core.node import Node
from amiro.navigation.slam import HectorSlam, SlamParams


class SlamNode(Node):
    """Maps from ``start`` (the map-frame pose of the first scan) with every lidar scan."""

    def __init__(self, start: Pose2D, params: SlamParams | None = None) -> None:
        super().__init__("slam")
        self.start_pose = start
        self.params = params or SlamParams()
        self.slam = HectorSlam(self.params, start)
        self.trajectory: list[tuple[float, Pose2D]] = []
        self._odom: Pose2D | None = None

    def on_start(self) -> None:
        self.pose_pub = self.create_publisher(names.SLAM_POSE, Pose2D)
        self.create_subscription(names.ODOM, Odometry, self._on_odom, depth=1)
        self.create_subscription(names.SCAN, LaserScan, self._on_scan, depth=1)

    def _on_odom(self, msg: Odometry) -> None:
        self._odom = msg.pose.to_pose2d()

    def _on_scan(self, scan: LaserScan) -> None:
        pose = self.slam.update(scan.ranges, scan.angles(), self._odom)
        self.trajectory.append((self.now(), pose))
        self.pose_pub.publish(pose)
