"""Assembles the navigation stack from a map_server map and the configuration."""

from __future__ import annotations

import math

import numpy as np

from amiro.core import names, registry
from amiro.core.config import ConfigError
from amiro.core.gridmap import GridMap
from amiro.core.messages import Pose2D
from amiro.navigation.amcl import AmclParams
from amiro.navigation.astar import warm_up
from amiro.navigation.config import NavigationConfig
from amiro.navigation.costmap import Costmap, GridFrame, downsample
from amiro.navigation.follower import FollowerLimits
from amiro.navigation.likelihood import LikelihoodField
from amiro.navigation.localization import AmclLocalizer, Localizer, OracleLocalizer
from amiro.navigation.move_to import MoveToNode

__all__ = [
    "amcl_localizer",
    "build_navigation",
    "costmap_from_map",
    "make_localizer",
    "oracle_localizer",
]


def costmap_from_map(grid: GridMap, cfg: NavigationConfig) -> Costmap:
    """Occupied and unknown cells are obstacles; the grid is coarsened for planning speed."""
    factor = max(1, round(cfg.planning_resolution / grid.resolution))
    blocked = downsample(np.asarray(grid.data) != 0, factor)
    ox, oy, _ = grid.origin
    frame = GridFrame(grid.resolution * factor, ox, oy, blocked.shape[0], blocked.shape[1])
    return Costmap(blocked, frame, cfg.robot_radius, cfg.safety_margin)


def amcl_localizer(
    grid: GridMap,
    cfg: NavigationConfig,
    initial_pose: Pose2D | None = None,
    rng: np.random.Generator | None = None,
) -> Localizer:
    params = AmclParams(max_particles=cfg.amcl_particles, beams=cfg.amcl_beams)
    return AmclLocalizer(LikelihoodField(grid), params, initial_pose, rng)


def oracle_localizer(
    grid: GridMap,
    cfg: NavigationConfig,
    initial_pose: Pose2D | None = None,
    rng: np.random.Generator | None = None,
) -> Localizer:
    return OracleLocalizer(names.GROUND_TRUTH)


def make_localizer(
    grid: GridMap,
    cfg: NavigationConfig,
    initial_pose: Pose2D | None = None,
    rng: np.random.Generator | None = None,
) -> Localizer:
    """The localiser ``cfg.localization`` names (:mod:`amiro.navigation.backends`)."""
    localizer: Localizer = registry.create(
        "localization", cfg.localization, grid, cfg, initial_pose, rng
    )
    return localizer


def build_navigation(
    grid: GridMap,
    places: dict[str, Pose2D],
    cfg: NavigationConfig,
    initial_pose: Pose2D | None = None,
    rng: np.random.Generator | None = None,
) -> MoveToNode:
    """The navigation node.  ``initial_pose`` seeds AMCL; without it, ``cfg.start_place``."""
    if cfg.backend == "nav2":
        raise ConfigError(
            "navigation.backend: nav2 makes MoveTo a client of a robot's own Nav2 over ROS 2: "
            "use it in a ROS 2 deployment's edge (amiro node / amiro launch)"
        )
    if initial_pose is None and cfg.start_place is not None:
        if cfg.start_place not in places:
            raise ConfigError(f"navigation.start_place: no place named {cfg.start_place!r}")
        initial_pose = places[cfg.start_place]
    limits = FollowerLimits(max_speed=cfg.max_speed, max_turn=min(cfg.max_turn, math.pi))
    warm_up()
    return MoveToNode(
        costmap_from_map(grid, cfg),
        places,
        make_localizer(grid, cfg, initial_pose, rng),
        limits,
        control_hz=cfg.control_hz,
    )
