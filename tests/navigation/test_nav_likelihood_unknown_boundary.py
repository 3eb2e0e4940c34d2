"""AMCL on a map that draws the building's walls as unknown (the free space simply ends,
as in the willow and robotis office maps): a scan at the true pose must fit, not read as
lost and make recovery scatter random particles."""

from __future__ import annotations

import numpy as np

from amiro.core.gridmap import UNKNOWN, GridMap
from amiro.core.messages import Pose2D
from amiro.home.world import World, default_home_path
from amiro.navigation.amcl import ParticleFilter
from amiro.navigation.likelihood import LikelihoodField, unknown_boundary
from amiro.sim.lidar import Lidar

WALLED = World.load(default_home_path()).live
POSE = Pose2D(2.0, 4.2, 0.3)


def _walls_unknown(grid: GridMap) -> GridMap:
    data = grid.data.copy()
    data[data > 50] = UNKNOWN
    return GridMap(data, grid.resolution, grid.origin)


def _tracked(grid: GridMap) -> ParticleFilter:
    """A filter started at the true pose after 20 scans taken there (cast on the walls)."""
    pf = ParticleFilter(LikelihoodField(grid), np.random.default_rng(1))
    pf.init_pose(POSE)
    rng, lidar = np.random.default_rng(0), Lidar()
    for i in range(20):
        pf.correct(lidar.scan(WALLED, POSE, 0.1 * i, rng))
    return pf


def test_a_scan_at_the_true_pose_is_not_lost_when_walls_are_unknown() -> None:
    pf = _tracked(_walls_unknown(WALLED))
    assert pf.inject_share() == 0.0
    assert pf.estimate().distance_to(POSE) < 0.1
    # it fits as well as on the map that draws the walls
    walled = _tracked(WALLED)
    assert pf.w_fast > 0.9 * walled.w_fast


def test_maps_that_draw_their_walls_keep_unknown_space_unexplained() -> None:
    assert unknown_boundary(WALLED) is None
    edge = unknown_boundary(_walls_unknown(WALLED))
    assert edge is not None
    # the edge is where the walls were, next to the free space
    assert edge.sum() > 0 and bool(np.all(WALLED.data[edge] > 50))
