"""Global planning on a costmap: to a pose, or to the best spot near a person."""

from __future__ import annotations

import math

import numpy as np

from amiro.core.messages import Point, Pose2D
from amiro.navigation.astar import Cell, astar, prune
from amiro.navigation.costmap import Costmap

_BERTH_M = 0.12  # shortcuts stay this much further from obstacles than the lethal zone


START_REACH_M = 0.3  # a robot inside an inflation zone starts from the nearest free cell
GOAL_TOLERANCE_M = 0.15  # how far from a goal in an inflation zone the path may end


class GlobalPlanner:
    def __init__(self, costmap: Costmap) -> None:
        self.costmap = costmap

    def _to_poses(self, cells: list[Cell], final_theta: float, start: Pose2D) -> list[Pose2D]:
        """Waypoints from the robot itself (not its cell's centre, up to half a cell away)."""
        frame = self.costmap.frame
        # Shortcuts must keep a wider berth than the lethal zone: Pepper's arms swing out.
        berth = self.costmap.clearance < self.costmap.inscribed + _BERTH_M
        pts = [frame.to_world(r, c) for r, c in prune(cells, berth)]
        if frame.to_cell(start.x, start.y) == cells[0]:
            pts[0] = (start.x, start.y)
        poses = []
        for i, (x, y) in enumerate(pts):
            if i + 1 < len(pts):
                nx, ny = pts[i + 1]
                theta = math.atan2(ny - y, nx - x)
            else:
                theta = final_theta
            poses.append(Pose2D(x, y, theta))
        return poses

    def _nearest_free(self, x: float, y: float, reach_m: float) -> Cell | None:
        """The cell at (x, y), or the nearest non-lethal one within ``reach_m`` of it."""
        frame = self.costmap.frame
        cell = frame.to_cell(x, y)
        if not frame.inside(*cell):
            return None
        lethal = self.costmap.lethal
        if not lethal[cell]:
            return cell
        r0, c0 = cell
        reach = math.ceil(reach_m / frame.resolution)
        best: tuple[float, Cell] | None = None
        for r in range(max(0, r0 - reach), min(frame.height, r0 + reach + 1)):
            for c in range(max(0, c0 - reach), min(frame.width, c0 + reach + 1)):
                d = (r - r0) ** 2 + (c - c0) ** 2
                if not lethal[r, c] and d <= reach * reach and (best is None or d < best[0]):
                    best = (d, (r, c))
        return None if best is None else best[1]

    def _start_cell(self, start: Pose2D) -> Cell | None:
        """The robot's cell, or the nearest free one when it stands inside an inflation zone."""
        return self._nearest_free(start.x, start.y, START_REACH_M)

    def plan_to_pose(self, start: Pose2D, goal: Pose2D) -> list[Pose2D] | None:
        """Path ending at ``goal``; a goal just inside an inflation zone (a place next to
        furniture, a waypoint by a door the lidar now shows closed) is reached at the nearest
        free cell within ``GOAL_TOLERANCE_M``, as planners' goal tolerance does."""
        s = self._start_cell(start)
        g = self._nearest_free(goal.x, goal.y, GOAL_TOLERANCE_M)
        if s is None or g is None:
            return None
        cells = astar(self.costmap.lethal, self.costmap.cost, s, {g})
        if cells is None:
            return None
        path = self._to_poses(cells, goal.theta, start)
        if g == self.costmap.frame.to_cell(goal.x, goal.y):
            path[-1] = goal
        else:
            x, y = self.costmap.frame.to_world(*g)
            path[-1] = Pose2D(x, y, goal.theta)
        return path

    def plan_near(
        self, start: Pose2D, target: Point, approach: float, tolerance: float = 0.25
    ) -> list[Pose2D] | None:
        """Path to a free spot ``approach`` metres from ``target``, facing it.

        Spots within a cell of the requested distance come first; only when none of them is
        reachable does the search widen to ``approach ± tolerance`` (a cheaper outer spot
        would otherwise always win: the ring's near edge is the robot's side).
        """
        s = self._start_cell(start)
        if s is None:
            return None
        frame = self.costmap.frame
        res = frame.resolution
        tr, tc = frame.to_cell(target.x, target.y)
        reach = math.ceil((approach + tolerance) / res) + 1
        rr, cc = np.meshgrid(
            np.arange(tr - reach, tr + reach + 1),
            np.arange(tc - reach, tc + reach + 1),
            indexing="ij",
        )
        inside = (rr >= 0) & (rr < frame.height) & (cc >= 0) & (cc < frame.width)
        xs = frame.origin_x + (cc + 0.5) * res
        ys = frame.origin_y + (rr + 0.5) * res
        off = np.abs(np.hypot(xs - target.x, ys - target.y) - approach)
        cells = None
        for band in (min(0.75 * res, tolerance), tolerance):
            ring = inside & (off <= band)
            goals = {(int(r), int(c)) for r, c in zip(rr[ring], cc[ring], strict=True)}
            cells = astar(self.costmap.lethal, self.costmap.cost, s, goals)
            if cells is not None:
                break
        if cells is None:
            return None
        gx, gy = frame.to_world(*cells[-1])
        facing = math.atan2(target.y - gy, target.x - gx)
        path = self._to_poses(cells, facing, start)
        path[-1] = Pose2D(gx, gy, facing)
        return path
