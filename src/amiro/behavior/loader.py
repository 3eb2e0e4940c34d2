"""Behaviours as YAML data: a task graph a non-programmer can read and edit.

::

    name: hydration
    priority: 5
    blackboard: {person: maria}
    entry: search
    tasks:
      search: {type: Search, params: {person: $person}, on_success: move,
               on_failure: {end: person_not_found}}

Every mistake (unknown task type, edge to an unknown task, missing entry) is a one-line
:class:`~amiro.core.config.ConfigError` naming the file and the offending key.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import yaml
from pydantic import field_validator

from amiro.behavior.graph import End, TaskGraph
from amiro.behavior.task import TaskError, make_task
from amiro.core.config import ConfigError, Section, parse, read_yaml


class EndSpec(Section):
    end: str


class TaskSpec(Section):
    type: str
    params: dict[str, Any] | None = None
    on_success: str | EndSpec | None = None
    on_failure: str | EndSpec | None = None

    @field_validator("on_success", "on_failure", mode="before")
    @classmethod
    def _edge(cls, value: Any) -> Any:
        """One clear message instead of pydantic's per-union-member errors."""
        if value is None or isinstance(value, str | EndSpec):
            return value
        if isinstance(value, dict) and set(value) == {"end"} and isinstance(value["end"], str):
            return EndSpec(end=value["end"])
        raise ValueError(f"an edge is a task id or {{end: outcome}}, got {value!r}")


class BehaviorSpec(Section):
    name: str
    priority: int = 0
    blackboard: dict[str, Any] | None = None
    entry: str
    tasks: dict[str, TaskSpec]


def build(spec: BehaviorSpec, source: str, overrides: Mapping[str, Any] | None = None) -> TaskGraph:
    """Turn a validated spec into a TaskGraph; ``overrides`` replace blackboard values."""
    if not spec.name:
        raise ConfigError(f"{source}: name: must not be empty")
    if not spec.tasks:
        raise ConfigError(f"{source}: tasks: a behaviour needs at least one task")
    known = ", ".join(sorted(spec.tasks))
    if spec.entry not in spec.tasks:
        raise ConfigError(f"{source}: entry: '{spec.entry}' is not a task (tasks: {known})")
    blackboard = {**(spec.blackboard or {}), **(overrides or {})}
    graph = TaskGraph(spec.name, spec.priority, blackboard=blackboard, entry=spec.entry)
    for task_id, ts in spec.tasks.items():
        try:
            task = make_task(ts.type, ts.params)
        except TaskError as exc:
            key = "type" if "unknown task type" in str(exc) else "params"
            raise ConfigError(f"{source}: tasks.{task_id}.{key}: {exc}") from None
        edges: dict[str, str | End | None] = {}
        for label, edge in (("on_success", ts.on_success), ("on_failure", ts.on_failure)):
            if isinstance(edge, EndSpec):
                if not edge.end:
                    raise ConfigError(f"{source}: tasks.{task_id}.{label}.end: must not be empty")
                edges[label] = End(edge.end)
            elif edge is not None and edge not in spec.tasks:
                raise ConfigError(
                    f"{source}: tasks.{task_id}.{label}: unknown task '{edge}' (tasks: {known})"
                )
            else:
                edges[label] = edge
        graph.add(task_id, task, on_success=edges["on_success"], on_failure=edges["on_failure"])
    try:
        graph.validate()
    except TaskError as exc:  # already checked above; kept as a safety net
        raise ConfigError(f"{source}: {exc}") from None
    return graph


def load_behavior_data(
    data: Any, source: str = "<data>", overrides: Mapping[str, Any] | None = None
) -> TaskGraph:
    """From already-parsed data (a dict), e.g. a behaviour embedded in a scenario file."""
    return build(parse(BehaviorSpec, data, source), source, overrides)


def loads_behavior(
    text: str, source: str = "<string>", overrides: Mapping[str, Any] | None = None
) -> TaskGraph:
    """From YAML text."""
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f" line {mark.line + 1}:" if mark is not None else ""
        problem = getattr(exc, "problem", None) or "invalid YAML"
        raise ConfigError(f"{source}:{where} {problem}") from None
    return load_behavior_data(data, source, overrides)


def load_behavior(path: str | Path, overrides: Mapping[str, Any] | None = None) -> TaskGraph:
    """From a YAML file."""
    return load_behavior_data(read_yaml(path), str(path), overrides)
