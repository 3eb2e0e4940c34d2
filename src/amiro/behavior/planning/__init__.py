"""Declarative planning (PDDL) and re-planning of the robot's errands (paper, section 3.7)."""

from amiro.behavior.planning.executive import PlanExecutive
from amiro.behavior.planning.knowledge import DoorState, KnowledgeBase
from amiro.behavior.planning.knowledge_node import KnowledgeNode
from amiro.behavior.planning.planner import HomePlanner, PlanningConfig, PlanOutcome, PlanStep
from amiro.behavior.planning.problem import Goal, RobotState
from amiro.behavior.planning.topology import Topology, grid_topology, topology_from_world

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
