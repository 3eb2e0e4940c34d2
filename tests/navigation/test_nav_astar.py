"""A* and path pruning on small synthetic grids."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from amiro.navigation.astar import Cell, astar, prune

SQRT2 = math.sqrt(2.0)


def _free(h: int, w: int) -> tuple[np.ndarray, np.ndarray]:
    return np.zeros((h, w), dtype=bool), np.zeros((h, w))


def _length(path: list[Cell]) -> float:
    return sum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in itertools.pairwise(path))


def _octile(a: Cell, b: Cell) -> float:
    dr, dc = abs(a[0] - b[0]), abs(a[1] - b[1])
    return max(dr, dc) + (SQRT2 - 1.0) * min(dr, dc)


def _assert_connected(path: list[Cell], lethal: np.ndarray) -> None:
    """8-connected steps, never on a lethal cell, never cutting a lethal corner."""
    for (r, c), (nr, nc) in itertools.pairwise(path):
        assert max(abs(nr - r), abs(nc - c)) == 1, f"jump {(r, c)} -> {(nr, nc)}"
        assert not lethal[nr, nc]
        if nr != r and nc != c:
            assert not lethal[r, nc] and not lethal[nr, c], f"corner cut at {(r, c)}"
    assert not lethal[path[0]]


def _crosses(a: Cell, b: Cell, cell: Cell) -> bool:
    """Does the segment between the centres of a and b enter the interior of ``cell``?

    Cells are unit squares around integer centres; grazing a corner or an edge does not count.
    """
    t0, t1 = 0.0, 1.0
    for k in (0, 1):
        p, d = a[k], b[k] - a[k]
        lo, hi = cell[k] - 0.5 + 1e-9, cell[k] + 0.5 - 1e-9
        if d == 0:
            if not lo < p < hi:
                return False
            continue
        ta, tb = (lo - p) / d, (hi - p) / d
        t0, t1 = max(t0, min(ta, tb)), min(t1, max(ta, tb))
    return t1 > t0


def _segment_clear(a: Cell, b: Cell, lethal: np.ndarray) -> bool:
    return not any(_crosses(a, b, (int(r), int(c))) for r, c in np.argwhere(lethal))


@pytest.mark.parametrize(
    ("start", "goal"), [((0, 0), (9, 14)), ((3, 12), (11, 1)), ((5, 5), (5, 13)), ((0, 7), (7, 0))]
)
def test_empty_grid_path_length_is_octile_distance(start: Cell, goal: Cell) -> None:
    lethal, cost = _free(12, 15)
    path = astar(lethal, cost, start, {goal})
    assert path is not None
    assert path[0] == start and path[-1] == goal
    _assert_connected(path, lethal)
    assert _length(path) == pytest.approx(_octile(start, goal))


def test_start_equals_goal_is_a_one_cell_path() -> None:
    lethal, cost = _free(5, 5)
    assert astar(lethal, cost, (2, 2), {(2, 2)}) == [(2, 2)]


def test_wall_with_a_gap_forces_the_path_through_the_gap() -> None:
    lethal, cost = _free(15, 15)
    lethal[:, 7] = True
    lethal[12, 7] = False  # the only gap, far from the straight line
    path = astar(lethal, cost, (2, 2), {(2, 12)})
    assert path is not None
    _assert_connected(path, lethal)
    # the gap is entered and left straight (a diagonal step into it would cut the wall's
    # corner), so the shortest way is: down to (12, 6), across the gap, back up
    assert path[path.index((12, 7)) - 1] == (12, 6)
    assert path[path.index((12, 7)) + 1] == (12, 8)
    expected = _octile((2, 2), (12, 6)) + 2.0 + _octile((12, 8), (2, 12))
    assert _length(path) == pytest.approx(expected)  # vs 10 cells through a solid-free grid


def test_enclosed_goal_has_no_path() -> None:
    lethal, cost = _free(12, 12)
    lethal[6:11, 6] = lethal[6:11, 10] = True
    lethal[6, 6:11] = lethal[10, 6:11] = True  # a closed box around (8, 8)
    assert astar(lethal, cost, (1, 1), {(8, 8)}) is None
    # and from inside the box, nothing outside is reachable
    assert astar(lethal, cost, (8, 8), {(1, 1), (0, 11)}) is None


def test_lethal_start_or_goal() -> None:
    lethal, cost = _free(8, 8)
    lethal[0, 0] = True
    lethal[7, 7] = True
    assert astar(lethal, cost, (0, 0), {(5, 5)}) is None  # start inside an obstacle
    assert astar(lethal, cost, (1, 1), {(7, 7)}) is None  # the only goal is lethal
    # lethal goals are dropped from a goal set; the free one is reached
    path = astar(lethal, cost, (1, 1), {(7, 7), (1, 6)})
    assert path is not None and path[-1] == (1, 6)


def test_nearest_of_several_goals_is_chosen() -> None:
    lethal, cost = _free(10, 10)
    path = astar(lethal, cost, (5, 5), {(0, 0), (5, 8), (9, 9)})
    assert path is not None and path[-1] == (5, 8)
    assert _length(path) == pytest.approx(3.0)


def test_no_corner_cutting_past_an_obstacle() -> None:
    lethal, cost = _free(3, 3)
    lethal[0, 1] = True
    # from (0, 0) to (1, 1) the diagonal step would brush the lethal (0, 1): go around
    path = astar(lethal, cost, (0, 0), {(1, 1)})
    assert path == [(0, 0), (1, 0), (1, 1)]
    # two diagonal obstacles leave only a corner-to-corner gap: no way through
    lethal2, cost2 = _free(2, 2)
    lethal2[0, 1] = lethal2[1, 0] = True
    assert astar(lethal2, cost2, (0, 0), {(1, 1)}) is None


def test_soft_cost_keeps_the_path_away_from_a_costly_band() -> None:
    lethal, cost = _free(11, 20)
    cost[5, 3:17] = 1.0  # a costly (not lethal) band on the straight line
    path = astar(lethal, cost, (5, 0), {(5, 19)}, cost_weight=4.0)
    assert path is not None
    on_band = sum(1 for r, c in path if cost[r, c] > 0)
    assert on_band == 0
    straight = astar(lethal, cost, (5, 0), {(5, 19)}, cost_weight=0.0)
    assert straight is not None and _length(straight) == pytest.approx(19.0)


def test_prune_shortens_and_keeps_segments_collision_free() -> None:
    rng = np.random.default_rng(7)
    checked = 0
    for _ in range(60):
        lethal = rng.random((25, 25)) < 0.25
        lethal[0, 0] = lethal[24, 24] = False
        path = astar(lethal, np.zeros(lethal.shape), (0, 0), {(24, 24)}, cost_weight=0.0)
        if path is None:
            continue
        pruned = prune(path, lethal)
        assert pruned[0] == path[0] and pruned[-1] == path[-1]
        assert set(pruned) <= set(path)
        assert len(pruned) <= len(path)
        assert _length(pruned) <= _length(path) + 1e-9
        for a, b in itertools.pairwise(pruned):
            assert _segment_clear(a, b, lethal), f"pruned segment {a} -> {b} enters an obstacle"
        checked += 1
    assert checked >= 20


def test_prune_around_a_single_corner() -> None:
    lethal, cost = _free(20, 20)
    lethal[5:20, 10] = True  # a wall from row 5 up; pass above it (rows < 5)
    path = astar(lethal, cost, (15, 2), {(15, 17)})
    assert path is not None
    pruned = prune(path, lethal)
    assert len(pruned) < len(path) and len(pruned) <= 5
    assert _length(pruned) < _length(path) - 1.0
    for a, b in itertools.pairwise(pruned):
        assert _segment_clear(a, b, lethal)


def test_prune_a_straight_free_path_to_its_ends() -> None:
    lethal, _ = _free(5, 10)
    path = [(2, c) for c in range(10)]
    assert prune(path, lethal) == [(2, 0), (2, 9)]
    assert prune(path[:2], lethal) == path[:2]


def test_prune_does_not_clip_a_corner_cell() -> None:
    # (0, 0) -> (1, 2) passes through the interior of (1, 1) for t in (0.5, 0.75);
    # sampling the segment every half cell (rows 0, .25, .5, .75, 1) never lands in it
    lethal, _ = _free(2, 3)
    lethal[1, 1] = True
    assert _crosses((0, 0), (1, 2), (1, 1))
    path = [(0, 0), (0, 1), (0, 2), (1, 2)]
    pruned = prune(path, lethal)
    assert pruned == [(0, 0), (0, 2), (1, 2)]
    for a, b in itertools.pairwise(pruned):
        assert _segment_clear(a, b, lethal)


def _dijkstra_cost(lethal: np.ndarray, step: np.ndarray, start: Cell, goal: Cell) -> float:
    """Reference optimum: scipy's Dijkstra over the same 8-connected, corner-safe graph."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import dijkstra

    h, w = lethal.shape
    src, dst, wts = [], [], []
    for r, c in itertools.product(range(h), range(w)):
        if lethal[r, c]:
            continue
        for dr, dc in itertools.product((-1, 0, 1), repeat=2):
            nr, nc = r + dr, c + dc
            if (dr, dc) == (0, 0) or not (0 <= nr < h and 0 <= nc < w) or lethal[nr, nc]:
                continue
            if dr and dc and (lethal[r, nc] or lethal[nr, c]):
                continue
            src.append(r * w + c)
            dst.append(nr * w + nc)
            wts.append(math.hypot(dr, dc) * step[nr, nc])
    graph = coo_matrix((wts, (src, dst)), shape=(h * w, h * w)).tocsr()
    dist = dijkstra(graph, indices=start[0] * w + start[1])
    return float(dist[goal[0] * w + goal[1]])


def test_path_cost_matches_dijkstra_on_random_soft_cost_grids() -> None:
    rng = np.random.default_rng(11)
    compared = 0
    for _ in range(25):
        lethal = rng.random((30, 30)) < 0.2
        cost = rng.random((30, 30))
        lethal[0, 0] = lethal[29, 29] = False
        best = _dijkstra_cost(lethal, 1.0 + 4.0 * cost, (0, 0), (29, 29))
        path = astar(lethal, cost, (0, 0), {(29, 29)}, cost_weight=4.0)
        if not math.isfinite(best):
            assert path is None
            continue
        assert path is not None
        _assert_connected(path, lethal)
        got = sum(
            math.hypot(b[0] - a[0], b[1] - a[1]) * (1.0 + 4.0 * cost[b])
            for a, b in itertools.pairwise(path)
        )
        assert got == pytest.approx(best, rel=1e-9)
        compared += 1
    assert compared >= 10
