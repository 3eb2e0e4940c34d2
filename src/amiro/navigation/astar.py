"""A* over a costmap, 8-connected, with an octile heuristic and soft obstacle costs."""

from __future__ import annotations

import heapq
import math

import numpy as np
import numpy.typing as npt

from amiro.navigation.costmap import BoolGrid, FloatGrid

_MOVES = [
    (-1, 0, 1.0),
    (1, 0, 1.0),
    (0, -1, 1.0),
    (0, 1, 1.0),
    (-1, -1, math.sqrt(2)),
    (-1, 1, math.sqrt(2)),
    (1, -1, math.sqrt(2)),
    (1, 1, math.sqrt(2)),
]

Cell = tuple[int, int]


def astar(
    lethal: BoolGrid,
    cost: FloatGrid,
    start: Cell,
    goals: set[Cell],
    cost_weight: float = 4.0,
) -> list[Cell] | None:
    """Cheapest path from ``start`` to any cell of ``goals``; None when there is none.

    Step cost is the move length times (1 + cost_weight * soft cost), so paths keep clear of
    obstacles when there is room and squeeze past them only when they must.
    """
    goals = {g for g in goals if not lethal[g]}
    if not goals or lethal[start]:
        return None
    h, w = lethal.shape
    goal_arr = np.array(sorted(goals))
    g_score: dict[Cell, float] = {start: 0.0}
    parent: dict[Cell, Cell] = {}
    heur_cache: dict[Cell, float] = {}
    frontier: list[tuple[float, float, Cell]] = [(_octile_to_nearest(start, goal_arr), 0.0, start)]
    closed: set[Cell] = set()
    step_cost = 1.0 + cost_weight * cost
    while frontier:
        _, g, cell = heapq.heappop(frontier)
        if cell in closed:
            continue
        if cell in goals:
            path = [cell]
            while cell in parent:
                cell = parent[cell]
                path.append(cell)
            return path[::-1]
        closed.add(cell)
        r, c = cell
        for dr, dc, length in _MOVES:
            nr, nc = r + dr, c + dc
            if not (0 <= nr < h and 0 <= nc < w) or lethal[nr, nc]:
                continue
            if dr and dc and (lethal[r, nc] or lethal[nr, c]):
                continue  # no corner cutting past an obstacle
            nxt = (nr, nc)
            ng = g + length * step_cost[nr, nc]
            if ng < g_score.get(nxt, math.inf):
                g_score[nxt] = ng
                parent[nxt] = cell
                hv = heur_cache.get(nxt)
                if hv is None:
                    hv = _octile_to_nearest(nxt, goal_arr)
                    heur_cache[nxt] = hv
                heapq.heappush(frontier, (ng + hv, ng, nxt))
    return None


def _octile_to_nearest(cell: Cell, goal_arr: npt.NDArray[np.int64]) -> float:
    """Admissible: every step costs at least its length."""
    dr = np.abs(goal_arr[:, 0] - cell[0])
    dc = np.abs(goal_arr[:, 1] - cell[1])
    return float((np.maximum(dr, dc) + (math.sqrt(2) - 1) * np.minimum(dr, dc)).min())


def prune(path: list[Cell], lethal: BoolGrid) -> list[Cell]:
    """Drop waypoints that a straight segment through free cells can skip."""
    if len(path) <= 2:
        return path
    out = [path[0]]
    anchor = 0
    for i in range(2, len(path)):
        if not _clear(path[anchor], path[i], lethal):
            out.append(path[i - 1])
            anchor = i - 1
    out.append(path[-1])
    return out


def _clear(a: Cell, b: Cell, lethal: BoolGrid) -> bool:
    """True when the segment between the cell centres enters no lethal cell's interior.

    Exact (slab clipping against every lethal cell of the bounding box): sampling the
    segment misses cells whose corner it clips.
    """
    r0, r1 = sorted((a[0], b[0]))
    c0, c1 = sorted((a[1], b[1]))
    rows, cols = np.nonzero(lethal[r0 : r1 + 1, c0 : c1 + 1])
    if rows.size == 0:
        return True
    half = 0.5 - 1e-9  # touching a corner or an edge is not entering the cell
    t_in = np.zeros(rows.size)
    t_out = np.ones(rows.size)
    for start, delta, centres in (
        (a[0], b[0] - a[0], rows + r0),
        (a[1], b[1] - a[1], cols + c0),
    ):
        if delta == 0:
            t_out = np.where(np.abs(centres - start) < half, t_out, -1.0)
        else:
            lo = (centres - half - start) / delta
            hi = (centres + half - start) / delta
            t_in = np.maximum(t_in, np.minimum(lo, hi))
            t_out = np.minimum(t_out, np.maximum(lo, hi))
    return not bool((t_out > t_in).any())
