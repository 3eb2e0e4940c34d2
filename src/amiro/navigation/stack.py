"""Assembles the navigation stack from a map_server map and the configuration."""

from __future__ import annotations

import math

import numpy as np

from amiro.core.gridmap import GridMap
from amiro.core.messages import Pose2D
from amiro.navigation.config import NavigationConfig
from amiro.navigation.costmap import Costmap, GridFrame, downsample
from amiro.navigation.follower import FollowerLimits
from amiro.navigation.move_to import MoveToNode

GROUND_TRUTH_TOPIC = "/amiro/sim/ground_truth"


def costmap_from_map(grid: GridMap, cfg: NavigationConfig) -> Costmap:
    """Occupied and unknown cells are obstacles; the grid is coarsened for planning speed."""
    factor = max(1, round(cfg.planning_resolution / grid.resolution))
    blocked = downsample(np.asarray(grid.data) != 0, factor)
    ox, oy, _ = grid.origin
    frame = GridFrame(grid.resolution * factor, ox, oy, blocked.shape[0], blocked.shape[1])
    return Costmap(blocked, frame, cfg.robot_radius, cfg.safety_margin)


def build_navigation(grid: GridMap, places: dict[str, Pose2D], cfg: NavigationConfig) -> MoveToNode:
    pose_topic = GROUND_TRUTH_TOPIC  # the only localisation so far is the oracle
    limits = FollowerLimits(max_speed=cfg.max_speed, max_turn=min(cfg.max_turn, math.pi))
    return MoveToNode(
        costmap_from_map(grid, cfg), places, pose_topic, limits, control_hz=cfg.control_hz
    )
