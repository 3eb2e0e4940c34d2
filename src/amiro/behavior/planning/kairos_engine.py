"""Kairos (Apache-2.0) behind unified-planning, without the cost of writing a home as PDDL.

up-kairos writes the problem with UP's PDDL writer, which reads ``problem.initial_values``:
every grounding of every fluent, true or false, although the writer skips the false ones (most
of a 10-room plan).  It also works out the problem's kind (another walk over every grounding)
nine times per plan.  This engine hands the writer the problem with its kind worked out once
and its initial values as set, plus every grounding of the fluents whose default is not false
(the temporal ``travel_time``), so the PDDL is the same.  Registered with unified-planning as
``amiro-kairos``; config engine ``kairos`` means this one.
"""

from __future__ import annotations

from typing import Any

import unified_planning as up
from unified_planning.engines import PlanGenerationResult
from unified_planning.model import FNode, Problem
from unified_planning.model.fluent import get_all_fluent_exp
from up_kairos.engine import KairosEngine  # type: ignore[import-untyped]

NAME = "amiro-kairos"
# Kairos' default search takes the detour through another room when a person could open the
# closed door on the way (one step more); lama with novelty finds the shorter plan, as
# pyperplan does, in the same time.
SEARCH = "lama-novelty"


class WrittenProblem:
    """The problem as the PDDL writer reads it; every other attribute is the problem's own."""

    def __init__(self, problem: Problem) -> None:
        self._problem = problem
        self.kind = problem.kind
        self.initial_values = written_initial_values(problem)

    def __getattr__(self, name: str) -> Any:
        return getattr(self._problem, name)


def written_initial_values(problem: Problem) -> dict[FNode, FNode]:
    """The initial values the PDDL writer needs: those set, and every grounding of a fluent
    whose default is not false (a false fact is written by leaving it out)."""
    values = dict(problem.explicit_initial_values)
    for fluent, default in problem.fluents_defaults.items():
        if default.is_false():
            continue
        for exp in get_all_fluent_exp(problem, fluent):
            values.setdefault(exp, default)
    return values


class HomeKairos(KairosEngine):  # type: ignore[misc]
    """up-kairos's engine, solving the problem as :class:`WrittenProblem` presents it."""

    def __init__(self, **options: Any) -> None:
        super().__init__(**({"search": SEARCH} | options))

    @property
    def name(self) -> str:
        return NAME

    def _solve_with_params(
        self, problem: up.model.AbstractProblem, *args: Any, **kwargs: Any
    ) -> PlanGenerationResult:
        assert isinstance(problem, Problem)
        return super()._solve_with_params(WrittenProblem(problem), *args, **kwargs)
