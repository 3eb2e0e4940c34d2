"""``amiro nav bench``: per-cycle costs of the navigation stack (wall time, median of runs)."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from amiro.core.gridmap import GridMap
from amiro.core.messages import Header, LaserScan, Pose2D, Twist
from amiro.home.world import World, default_home_path
from amiro.navigation.amcl import AmclParams, ParticleFilter
from amiro.navigation.astar import astar
from amiro.navigation.costmap import Costmap, GridFrame
from amiro.navigation.dwa import DynamicWindow
from amiro.navigation.likelihood import LikelihoodField
from amiro.navigation.slam import HectorSlam
from amiro.sim.lidar import Lidar


def _median_ms(fn: Callable[[], object], repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return round(1000.0 * float(np.median(times)), 3)


def run_bench(rng: np.random.Generator) -> dict[str, Any]:
    world = World.load(default_home_path())
    grid: GridMap = world.live
    pose = world.place("hallway")
    scan_ranges = Lidar().true_ranges(grid, pose)
    scan = LaserScan(
        Header(), -math.pi, math.pi, 2 * math.pi / 360, 0.0, 0.1, 0.15, 12.0, scan_ranges
    )

    big = np.zeros((1000, 1000), dtype=bool)
    big[200:800, 500] = True  # a long wall to go around
    lethal, cost = big, np.zeros(big.shape)
    astar(lethal, cost, (0, 0), {(0, 1)})  # loads (or compiles) the numba kernel once
    astar_ms = _median_ms(lambda: astar(lethal, cost, (500, 10), {(500, 990)}), 5)

    costmap = Costmap(
        grid.data != 0, GridFrame(grid.resolution, *grid.origin[:2], grid.height, grid.width)
    )
    dwa = DynamicWindow(costmap)
    pref = Twist.planar(0.3, 0.0, 0.1)
    dwa_ms = _median_ms(lambda: dwa.command(pose, (0.3, 0.0, 0.0), pref), 50)

    slam = HectorSlam()
    angles = scan.angles()
    slam.update(scan_ranges, angles, Pose2D())
    slam_ms = _median_ms(lambda: slam.update(scan_ranges, angles, Pose2D()), 20)

    pf = ParticleFilter(LikelihoodField(grid), rng, AmclParams(max_particles=500))
    pf.init_pose(pose)
    amcl_ms = _median_ms(lambda: pf.correct(scan), 20)
    return {
        "astar_1000x1000_ms": astar_ms,
        "dwa_cycle_ms": dwa_ms,
        "slam_scan_ms": slam_ms,
        "amcl_500_particles_ms": amcl_ms,
        "targets_ms": {"astar": 100, "dwa": 5, "slam": 20, "amcl": 10},
    }
