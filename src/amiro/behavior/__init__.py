"""Behaviour composition: task graphs, their YAML form, the engine and event handlers.

The names below load their submodule on first use (PEP 562), so importing a subpackage such
as ``amiro.commands.planning`` (``amiro --help``) does not load the engine.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from amiro.core.lazy import lazy_getattr

if TYPE_CHECKING:
    from amiro.behavior.checkpoint import Checkpoint, CheckpointError, FinishedTask
    from amiro.behavior.engine import BehaviorEngine, EngineConfig, GraphRun, RunStatus
    from amiro.behavior.graph import COMPLETED, FAILED, Edge, End, TaskGraph, TaskNode
    from amiro.behavior.handlers import (
        HandlerError,
        HandlerFactory,
        HandlerRegistry,
        yaml_handler,
    )
    from amiro.behavior.loader import load_behavior, load_behavior_data, loads_behavior
    from amiro.behavior.task import (
        Task,
        TaskContext,
        TaskError,
        TaskParams,
        TaskRecord,
        TaskStatus,
        make_task,
        task_types,
    )

_SUBMODULES = ("engine", "graph", "handlers", "loader", "task", "checkpoint")

__all__ = [
    "COMPLETED",
    "FAILED",
    "BehaviorEngine",
    "Checkpoint",
    "CheckpointError",
    "Edge",
    "End",
    "EngineConfig",
    "FinishedTask",
    "GraphRun",
    "HandlerError",
    "HandlerFactory",
    "HandlerRegistry",
    "RunStatus",
    "Task",
    "TaskContext",
    "TaskError",
    "TaskGraph",
    "TaskNode",
    "TaskParams",
    "TaskRecord",
    "TaskStatus",
    "load_behavior",
    "load_behavior_data",
    "loads_behavior",
    "make_task",
    "task_types",
    "yaml_handler",
]


__getattr__ = lazy_getattr(__name__, __all__, _SUBMODULES)
