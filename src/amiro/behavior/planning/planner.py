"""Planning through unified-planning with the engine chosen in config.

``kairos`` (Apache-2.0, through :mod:`.kairos_engine`) is the default: classical, or temporal
with durations from distances.  The GPL engines are optional (extra ``planners-gpl``):
``pyperplan`` (through :mod:`.pyperplan_engine`, which keeps the grounded task between plans,
the fastest re-plans) and ``fast-downward``.  A planner keeps its engine for its life, so
re-planning skips the start-up.
When no plan exists the outcome carries an explanation in words (see :mod:`.explain`).
"""

from __future__ import annotations

import importlib
import time
from dataclasses import dataclass, field
from typing import Any

from unified_planning.engines import PlanGenerationResultStatus as Status
from unified_planning.model import Problem
from unified_planning.plans import SequentialPlan, TimeTriggeredPlan
from unified_planning.shortcuts import OneshotPlanner

from amiro.behavior.planning.config import PlanningConfig
from amiro.behavior.planning.domain import home_domain
from amiro.behavior.planning.environment import add_engine, planning_environment
from amiro.behavior.planning.explain import explain_no_plan
from amiro.behavior.planning.knowledge import KnowledgeBase
from amiro.behavior.planning.problem import Goal, RobotState, make_problem
from amiro.core.config import ConfigError

_PACKAGES = {
    "kairos": "up_kairos",
    "pyperplan": "up_pyperplan",
    "fast-downward": "up_fast_downward",
}
_EXTRAS = {"pyperplan": "planners-gpl", "fast-downward": "planners-gpl"}
# config name -> the engine's name in unified-planning, its module and class
_UP_ENGINES = {
    "kairos": ("amiro-kairos", "amiro.behavior.planning.kairos_engine", "HomeKairos"),
    "pyperplan": ("amiro-pyperplan", "amiro.behavior.planning.pyperplan_engine", "CachedPyperplan"),
    "fast-downward": ("fast-downward", "up_fast_downward", "FastDownwardPDDLPlanner"),
}
_SOLVED = (Status.SOLVED_SATISFICING, Status.SOLVED_OPTIMALLY)


@dataclass(frozen=True, slots=True)
class PlanStep:
    action: str
    args: tuple[str, ...]
    start_s: float | None = None
    duration_s: float | None = None

    def __str__(self) -> str:
        return f"{self.action}({', '.join(self.args)})"

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {"action": self.action, "args": list(self.args)}
        if self.start_s is not None:
            out["start_s"] = self.start_s
            out["duration_s"] = self.duration_s
        return out


@dataclass
class PlanOutcome:
    engine: str
    status: str
    planning_ms: float
    steps: list[PlanStep] = field(default_factory=list)
    explanation: str = ""

    @property
    def solved(self) -> bool:
        return self.status in {s.name for s in _SOLVED}

    def to_dict(self) -> dict[str, Any]:
        return {
            "engine": self.engine,
            "status": self.status,
            "planning_ms": round(self.planning_ms, 2),
            "steps": [s.to_dict() for s in self.steps],
            "explanation": self.explanation,
        }


def engine_available(engine: str) -> bool:
    try:
        importlib.import_module(_PACKAGES[engine])
    except ImportError:
        return False
    return True


def require_engine(engine: str) -> None:
    """A one-line ConfigError saying what to install when the engine's package is missing."""
    if not engine_available(engine):
        package = _PACKAGES[engine].replace("_", "-")
        extra = _EXTRAS.get(engine)
        install = f"pip install 'amiro[{extra}]'" if extra else f"pip install {package}"
        raise ConfigError(f"planning engine {engine} needs the package {package}: {install}")


def open_engine(engine: str) -> Any:
    """The unified-planning engine for a config name, its package imported only now."""
    require_engine(engine)
    name, module, class_name = _UP_ENGINES[engine]
    add_engine(planning_environment(), name, module, class_name)
    return OneshotPlanner(name=name)


def solve(planner: Any, problem: Problem, timeout_s: float | None) -> tuple[str, list[PlanStep]]:
    result = planner.solve(problem, timeout=timeout_s)
    if result.status not in _SOLVED or result.plan is None:
        return result.status.name, []
    return result.status.name, _steps(result.plan)


def _steps(plan: Any) -> list[PlanStep]:
    if isinstance(plan, SequentialPlan):
        return [
            PlanStep(a.action.name, tuple(str(p) for p in a.actual_parameters))
            for a in plan.actions
        ]
    if isinstance(plan, TimeTriggeredPlan):
        return [
            PlanStep(
                a.action.name,
                tuple(str(p) for p in a.actual_parameters),
                float(start),
                None if duration is None else float(duration),
            )
            for start, a, duration in plan.timed_actions
        ]
    raise ConfigError(f"unsupported plan kind {type(plan).__name__}")


class HomePlanner:
    """Builds the problem from the knowledge base and plans with the configured engine."""

    def __init__(self, config: PlanningConfig | None = None) -> None:
        self.config = config or PlanningConfig()
        require_engine(self.config.engine)  # before a run starts, not at its first plan
        self.domain = home_domain(self.config.temporal)
        self._engine: Any = None  # opened on the first plan

    def problem(self, kb: KnowledgeBase, robot: RobotState, goals: list[Goal]) -> Problem:
        return make_problem(self.domain, kb, robot, goals, self.config.speed_mps)

    def plan(self, kb: KnowledgeBase, robot: RobotState, goals: list[Goal]) -> PlanOutcome:
        started = time.perf_counter()
        problem = self.problem(kb, robot, goals)
        if self._engine is None:
            self._engine = open_engine(self.config.engine)
        # pyperplan has no timeout and warns when given one
        timeout = None if self.config.engine == "pyperplan" else self.config.timeout_s
        status, steps = solve(self._engine, problem, timeout)
        elapsed_ms = (time.perf_counter() - started) * 1000.0
        outcome = PlanOutcome(self.config.engine, status, elapsed_ms, steps)
        if not steps:
            outcome.explanation = explain_no_plan(kb, robot, goals)
        return outcome
