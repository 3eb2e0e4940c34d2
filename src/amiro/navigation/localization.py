"""Where the robot is in the map: the navigation node's pose sources.

``AmclLocalizer`` runs the particle filter on ``/odom`` + ``/scan`` and reports a pose at
odometry rate (the last filter estimate carried forward by odometry); ``OracleLocalizer``
reads the simulator's ground truth, for tests and for comparing against a perfect pose.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Protocol

import numpy as np

from amiro.core import names
from amiro.core.messages import LaserScan, Odometry, Pose2D, PoseStamped
from amiro.core.node import Node
from amiro.navigation.amcl import AmclParams, ParticleFilter
from amiro.navigation.likelihood import LikelihoodField
from amiro.navigation.poses import between, compose

PoseCallback = Callable[[Pose2D], None]


class Localizer(Protocol):
    def attach(self, node: Node, on_pose: PoseCallback) -> None:
        """Subscribe on ``node``'s behalf and call ``on_pose`` with every new estimate."""


class OracleLocalizer:
    def __init__(self, topic: str = names.GROUND_TRUTH) -> None:
        self.topic = topic

    def attach(self, node: Node, on_pose: PoseCallback) -> None:
        node.create_subscription(self.topic, Pose2D, on_pose, depth=1)


class AmclLocalizer:
    """Particle filter on the bus; ``initial_pose`` None starts from global localisation.

    ``/initialpose`` re-seeds the belief around a pose; the ``/global_localization`` service
    (any request; answers the particle count) spreads it over the whole free space.

    Without an ``rng`` the filter draws from a child of the runtime's seeded generator.
    """

    def __init__(
        self,
        field: LikelihoodField,
        params: AmclParams | None = None,
        initial_pose: Pose2D | None = None,
        rng: np.random.Generator | None = None,
    ) -> None:
        self.field = field
        self.params = params or AmclParams()
        self.initial_pose = initial_pose
        self.rng = rng
        self.pf: ParticleFilter | None = None
        self._anchor: tuple[Pose2D, Pose2D] | None = None  # (map estimate, odom) at a fix
        self._odom: Pose2D | None = None
        self._on_pose: PoseCallback = lambda _pose: None

    def attach(self, node: Node, on_pose: PoseCallback) -> None:
        self._on_pose = on_pose
        self._pub = node.create_publisher(names.LOCALIZATION, Pose2D)
        rng = self.rng if self.rng is not None else node.runtime.rng.spawn(1)[0]
        self.pf = pf = ParticleFilter(self.field, rng, self.params)
        if self.initial_pose is None:
            pf.global_localization()
        else:
            pf.init_pose(self.initial_pose)
        self._anchor = None
        self._odom = None
        node.create_subscription(names.ODOM, Odometry, self._on_odom, depth=1)
        node.create_subscription(names.SCAN, LaserScan, self._on_scan, depth=1)
        node.create_subscription(names.INITIAL_POSE, PoseStamped, self._on_initial_pose)
        node.create_service(names.GLOBAL_LOCALIZATION, self.global_localization)

    def global_localization(self, _request: object = None) -> int:
        """Forget the pose: the robot could be anywhere; returns the particle count."""
        assert self.pf is not None
        self.pf.global_localization()
        self._fix()
        return len(self.pf.particles)

    def _on_initial_pose(self, msg: PoseStamped) -> None:
        assert self.pf is not None
        self.pf.init_pose(msg.pose.to_pose2d())
        self._fix()

    def _on_odom(self, msg: Odometry) -> None:
        assert self.pf is not None
        self._odom = msg.pose.to_pose2d()
        if self._anchor is None and self.initial_pose is not None:
            self._fix()  # a known start is a pose at once, before the first scan
        elif self._anchor is not None:
            est, odom = self._anchor
            self._emit(compose(est, between(odom, self._odom)))

    def _on_scan(self, scan: LaserScan) -> None:
        pf = self.pf
        if self._odom is None or pf is None:
            return
        # a wide belief is refined on every scan, even standing still (amcl's nomotion update)
        odom = self._odom
        if self._anchor is None or pf.moved_enough(odom) or pf.spread() > self.LOST_SPREAD_M:
            pf.predict(odom)
            pf.correct(scan)
            self._fix()

    LOST_SPREAD_M = 0.3

    def _fix(self) -> None:
        if self._odom is None or self.pf is None:
            return
        est = self.pf.estimate()
        self._anchor = (est, self._odom)
        self._emit(est)

    def _emit(self, pose: Pose2D) -> None:
        self._on_pose(pose)
        self._pub.publish(pose)
