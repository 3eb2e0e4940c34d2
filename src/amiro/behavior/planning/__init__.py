"""Declarative planning (PDDL) and re-planning of the robot's errands (paper, section 3.7).

The names load their submodule on first use, so ``amiro.commands.planning`` (built for
``amiro --help``) does not load the planners.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from amiro.core.lazy import lazy_getattr

if TYPE_CHECKING:
    from amiro.behavior.planning.config import PlanningConfig
    from amiro.behavior.planning.executive import PlanExecutive
    from amiro.behavior.planning.knowledge import DoorState, KnowledgeBase
    from amiro.behavior.planning.knowledge_node import KnowledgeNode
    from amiro.behavior.planning.planner import HomePlanner, PlanOutcome, PlanStep
    from amiro.behavior.planning.problem import Goal, RobotState
    from amiro.behavior.planning.topology import Topology, grid_topology, topology_from_world

_SUBMODULES = (
    "config",
    "executive",
    "knowledge",
    "knowledge_node",
    "planner",
    "problem",
    "topology",
)

__all__ = [
    "DoorState",
    "Goal",
    "HomePlanner",
    "KnowledgeBase",
    "KnowledgeNode",
    "PlanExecutive",
    "PlanOutcome",
    "PlanStep",
    "PlanningConfig",
    "RobotState",
    "Topology",
    "grid_topology",
    "topology_from_world",
]

__getattr__ = lazy_getattr(__name__, __all__, _SUBMODULES)
