"""``navigation.backend: nav2``: MoveTo on the edge's bus is a client of the robot's own Nav2.

Goals go to ``/navigate_to_pose`` (places resolved to their pose, a person to a pose
``approach`` metres short of her); Nav2's feedback becomes MoveTo's, its result codes
MoveTo's failure reasons (:func:`amiro.deploy.codecs.nav2_reason`), and cancelling a
MoveTo cancels the Nav2 goal.  The behaviour tasks read the robot's pose from the bridged
localisation topic, as when MoveTo runs in another amiro process.
"""

from __future__ import annotations

from amiro.core.runtime import Runtime
from amiro.deploy.boundary import NavigationState
from amiro.deploy.cloud import pose_topic
from amiro.deploy.codecs import NavigateToPoseCodec
from amiro.home.world import World
from amiro.ros2.actions import RemoteActionServer
from amiro.ros2.context import RosContext
from amiro.system import SystemConfig


def uses_nav2(cfg: SystemConfig) -> bool:
    return cfg.navigation.backend == "nav2"


def add_nav2_move_to(
    runtime: Runtime, ros: RosContext, cfg: SystemConfig, world: World, timeout_s: float
) -> RemoteActionServer:
    """MoveTo for the edge's bus, served by the robot's ``/navigate_to_pose``."""
    pose = NavigationState(runtime.bus, pose_topic(cfg))
    places = {name: world.place(name) for name in world.home.places}
    codec = NavigateToPoseCodec(places, lambda: pose.pose)
    return runtime.add(RemoteActionServer(ros, codec, timeout_s))
