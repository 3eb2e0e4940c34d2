"""pyperplan behind unified-planning, fast when the robot plans again in the same home.

up-pyperplan reads ``problem.initial_values``, which enumerates every grounding of every
fluent, true or false (most of the planning time for 10 rooms), then grounds the task from
scratch.  This engine reads only the facts set true (every fluent of a home problem defaults
to false) and keeps the grounded task per home shape: objects, static facts and goals.  A
re-plan after a door closed or a person refused help changes only dynamic facts, so only the
search runs again.  Registered with unified-planning as ``amiro-pyperplan``; config engine
``pyperplan`` means this one.
"""

from __future__ import annotations

import time
from collections import OrderedDict
from collections.abc import Hashable
from typing import Any

import unified_planning as up
from pyperplan.grounding import _get_partial_state, _get_statics
from pyperplan.pddl.pddl import Predicate
from pyperplan.planner import _ground, _search
from pyperplan.task import Task
from unified_planning.engines import PlanGenerationResult
from unified_planning.engines import PlanGenerationResultStatus as Status
from unified_planning.model import Problem
from unified_planning.plans import SequentialPlan
from up_pyperplan.engine import EngineImpl  # type: ignore[import-untyped]

NAME = "amiro-pyperplan"
CACHED_TASKS = 16  # grounded tasks kept: a home has few shapes (robot room, people's rooms)


class CachedPyperplan(EngineImpl):  # type: ignore[misc]
    """up-pyperplan's engine with true-facts-only conversion and a cache of grounded tasks."""

    def __init__(self, **options: Any) -> None:
        super().__init__(**options)
        self._grounded: OrderedDict[Hashable, Any] = OrderedDict()
        self.cache_hits = 0

    @property
    def name(self) -> str:
        return NAME

    def _convert_initial_values(self, problem: Problem) -> list[Any]:
        if any(v.is_true() for v in problem.fluents_defaults.values()):
            return super()._convert_initial_values(problem)  # type: ignore[no-any-return]
        return [
            Predicate(
                fact.fluent().name,
                [(o.object().name, self._convert_type(o.object().type)) for o in fact.args],
            )
            for fact, value in problem.explicit_initial_values.items()
            if value.is_true()
        ]

    def _solve(
        self,
        problem: up.model.AbstractProblem,
        heuristic: Any = None,
        timeout: float | None = None,
        output_stream: Any = None,
    ) -> PlanGenerationResult:
        assert isinstance(problem, Problem)
        started = time.perf_counter()
        self.pyp_types: dict[str, Any] = {}
        pyp_problem = self._convert_problem(self._convert_domain(problem), problem)
        task = self._task(pyp_problem)
        h = None if self._heuristic is None else self._heuristic(task)
        solution = _search(task, self._search, h)
        metrics = {"engine_internal_time": str(time.perf_counter() - started)}
        if solution is None:
            return PlanGenerationResult(Status.UNSOLVABLE_PROVEN, None, self.name, metrics=metrics)
        plan = SequentialPlan(
            [self._convert_string_to_action_instance(op.name, problem) for op in solution]
        )
        return PlanGenerationResult(Status.SOLVED_SATISFICING, plan, self.name, metrics=metrics)

    def _task(self, pyp_problem: Any) -> Any:
        """The grounded task of this home shape, grounded now or cached, from this state."""
        domain = pyp_problem.domain
        statics = set(_get_statics(domain.predicates.values(), domain.actions.values()))
        goals = _get_partial_state(pyp_problem.goal)
        key = (
            tuple(sorted(domain.actions)),
            frozenset((o, t.name) for o, t in pyp_problem.objects.items()),
            _get_partial_state(p for p in pyp_problem.initial_state if p.name in statics),
            goals,
        )
        cached = self._grounded.get(key)
        if cached is None:
            cached = _ground(pyp_problem)
            self._grounded[key] = cached
            if len(self._grounded) > CACHED_TASKS:
                self._grounded.popitem(last=False)
            return cached
        self.cache_hits += 1
        self._grounded.move_to_end(key)
        state = _get_partial_state(pyp_problem.initial_state) & cached.facts
        return Task(cached.name, cached.facts, state, cached.goals, cached.operators)
