"""Graph SLAM: the Hector-style submap front end, loop closures and a pose-graph back end.

Every ``keyframe_m`` of travel (or ``keyframe_rad`` of turning) the front-end pose becomes a
pose-graph node, tied to the previous one by the front end's relative motion; loop closures
against older submaps add edges across the graph, and the graph is re-optimised after every
few of them.  Scans between keyframes ride on their keyframe, so the whole trajectory and
the map (rebuilt from the keyframes' scans at their optimised poses) follow the correction.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from amiro.core.gridmap import GridMap
from amiro.core.messages import Pose2D
from amiro.navigation.field_match import FIELD_SIGMA_M
from amiro.navigation.loop_closure import LoopCloser, LoopParams
from amiro.navigation.occupancy import LogOddsGrid
from amiro.navigation.posegraph import PoseGraph
from amiro.navigation.poses import between, compose
from amiro.navigation.slam import SlamParams
from amiro.navigation.submaps import SubmapFrontEnd

FloatArray = npt.NDArray[np.float64]


# beams are free only up to 3 sigma of a 1 %-of-range lidar noise short of their hit (see
# LogOddsGrid): without it the front end over-estimates travel along corridors by ~1.5 %
LIDAR_FREE_MARGIN = 0.03
# the submaps forget after a few contrary observations (log-odds within +-2, not +-6): a wall
# is first drawn from 12 m away (12 cm range noise) and must give way to the sharper views as
# the robot comes closer, else the front end under-estimates travel by 0.4-0.8 %
TRACKING_CLAMP = 2.0
# a match further from the odometry guess than this many of the odometry's own sigmas (over
# that scan step) has slid along a corridor or onto a door one further, and is refused
GATE_SIGMAS = 3.0


def tracking_params(max_range: float = 12.0) -> SlamParams:
    """The front end's scan-matching settings for a lidar of ``max_range``."""
    return SlamParams(
        max_range=max_range,
        free_margin=LIDAR_FREE_MARGIN,
        clamp=TRACKING_CLAMP,
        gate_sigmas=GATE_SIGMAS,
        field_sigma=FIELD_SIGMA_M,
    )


@dataclass(frozen=True)
class GraphSlamParams:
    slam: SlamParams = field(default_factory=tracking_params)
    loop: LoopParams = field(default_factory=LoopParams)
    loop_closure: bool = True
    submap_m: float = 8.0
    keyframe_m: float = 0.5
    keyframe_rad: float = 0.3
    loop_check_m: float = 1.0  # travel between loop-closure searches
    loop_cloud_m: float = 4.0  # a loop query joins the scans of this much recent travel
    loop_cloud_points: int = 200
    optimize_every: int = 5  # loop edges between optimisations
    iterations_online: int = 8  # per optimisation while mapping (the final one runs longer)
    # front-end edge: sigma = base + per metre moved (x, y) / per radian turned (theta)
    step_sigma_xy: tuple[float, float] = (0.01, 0.03)
    step_sigma_theta: tuple[float, float] = (0.003, 0.02)
    loop_sigma: tuple[float, float, float] = (0.05, 0.05, 0.01)


@dataclass(frozen=True)
class _Keyframe:
    frontend: Pose2D
    travel: float
    px: npt.NDArray[np.float32]
    py: npt.NDArray[np.float32]


class GraphSlam:
    """Feed ``update(ranges, angles, odom)`` per scan, then ``finish()``; read
    ``trajectory()`` (one optimised pose per scan) and ``map()``."""

    def __init__(self, params: GraphSlamParams | None = None) -> None:
        self.params = p = params or GraphSlamParams()
        self.frontend = SubmapFrontEnd(p.slam, p.submap_m)
        self.loops = LoopCloser(p.loop)
        self.graph = PoseGraph()
        self.keyframes: list[_Keyframe] = []
        self.loop_closures = 0
        self.backend_seconds = 0.0  # CPU time, only to report the back end's cost
        self._scan_keyframe: list[tuple[int, Pose2D]] = []
        self._travel = 0.0
        self._last_check = -math.inf
        self._last_closure = 0.0
        self._pending = 0

    def update(self, ranges: FloatArray, angles: FloatArray, odom: Pose2D | None = None) -> Pose2D:
        """Add one scan; returns the current estimate in the map (graph) frame."""
        p = self.params
        ok = np.isfinite(ranges) & (ranges > 0.05) & (ranges < p.slam.max_range)
        px = ranges[ok] * np.cos(angles[ok])
        py = ranges[ok] * np.sin(angles[ok])
        before = self.frontend.pose
        pose = self.frontend.track(px, py, odom)
        if self._scan_keyframe:
            self._travel += before.distance_to(pose)
        keyframe = self._maybe_add_keyframe(pose, px, py)
        if keyframe is not None or self.frontend.should_insert():
            finished = self.frontend.insert(px, py, keyframe)
            if finished is not None:
                self.loops.add(finished, self._travel)
        k = len(self.keyframes) - 1
        rel = between(self.keyframes[k].frontend, pose)
        self._scan_keyframe.append((k, rel))
        if keyframe is not None and p.loop_closure:
            t0 = time.process_time()
            self._close_loops(keyframe)
            self.backend_seconds += time.process_time() - t0
        return compose(self.graph.pose(k), rel)

    def _maybe_add_keyframe(self, pose: Pose2D, px: FloatArray, py: FloatArray) -> int | None:
        p = self.params
        if self.keyframes:
            last = self.keyframes[-1]
            d = between(last.frontend, pose)
            dist = math.hypot(d.x, d.y)
            if dist < p.keyframe_m and abs(d.theta) < p.keyframe_rad:
                return None
            prev = len(self.keyframes) - 1
            k = self.graph.add_node(compose(self.graph.pose(prev), d))
            sxy = p.step_sigma_xy[0] + p.step_sigma_xy[1] * dist
            sth = p.step_sigma_theta[0] + p.step_sigma_theta[1] * (dist + abs(d.theta))
            self.graph.add_edge(prev, k, d, (sxy, sxy, sth))
        else:
            k = self.graph.add_node(Pose2D())
        self.keyframes.append(
            _Keyframe(pose, self._travel, px.astype(np.float32), py.astype(np.float32))
        )
        return k

    def _local_cloud(self, k: int) -> tuple[FloatArray, FloatArray]:
        """The scans of the last ``loop_cloud_m`` of travel in keyframe k's frame: one scan
        of a corridor fits many places, a few metres of them far fewer."""
        p = self.params
        here = self.keyframes[k]
        xs, ys = [], []
        for kf in reversed(self.keyframes[: k + 1]):
            if here.travel - kf.travel > p.loop_cloud_m:
                break
            rel = between(here.frontend, kf.frontend)
            c, s = math.cos(rel.theta), math.sin(rel.theta)
            xs.append(rel.x + c * kf.px - s * kf.py)
            ys.append(rel.y + s * kf.px + c * kf.py)
        px = np.concatenate(xs).astype(np.float64)
        py = np.concatenate(ys).astype(np.float64)
        stride = max(1, len(px) // p.loop_cloud_points)
        return px[::stride], py[::stride]

    def _close_loops(self, k: int) -> None:
        p = self.params
        if self._travel - self._last_check < p.loop_check_m:
            return
        self._last_check = self._travel
        px, py = self._local_cloud(k)
        since = self._travel - self._last_closure
        edges = self.loops.search(k, px, py, self.graph.poses, self._travel, since)
        for edge in edges:
            self.graph.add_edge(edge.anchor, edge.keyframe, edge.z, p.loop_sigma, robust=True)
        if not edges:
            return
        self.loop_closures += len(edges)
        self._pending += len(edges)
        self._last_closure = self._travel
        if self._pending >= p.optimize_every or since > 2.0 * p.submap_m:
            self.graph.optimize(iterations=p.iterations_online)
            self._pending = 0

    def finish(self) -> None:
        """Final optimisation over every edge, run to convergence."""
        if self.loop_closures:
            t0 = time.process_time()
            self.graph.optimize()
            self._pending = 0
            self.backend_seconds += time.process_time() - t0

    def trajectory(self) -> list[Pose2D]:
        return [compose(self.graph.pose(k), rel) for k, rel in self._scan_keyframe]

    def map(self) -> GridMap:
        """The finest occupancy grid, rebuilt from every keyframe at its optimised pose."""
        p = self.params.slam
        poses = self.graph.poses
        margin = p.max_range + 1.0
        lo = poses[:, :2].min(axis=0) - margin
        hi = poses[:, :2].max(axis=0) + margin
        size = hi - lo
        grid = LogOddsGrid(
            float(size[0]), float(size[1]), p.resolution, (lo[0], lo[1]), p.free_margin, p.clamp
        )
        for k, kf in enumerate(self.keyframes):
            x, y, th = poses[k]
            c, s = math.cos(th), math.sin(th)
            px, py = kf.px.astype(np.float64), kf.py.astype(np.float64)
            grid.integrate(x, y, x + c * px - s * py, y + s * px + c * py)
        return grid.to_gridmap()
