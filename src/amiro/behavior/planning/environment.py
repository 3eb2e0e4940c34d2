"""unified-planning's environment, made without loading the GPL engines.

UP's engine factory imports, when the environment is first made, every engine it knows that is
installed: with the extra ``planners-gpl`` that would load pyperplan and Fast Downward (GPL) in
every run, whatever the config says.  amiro makes the environment with those packages hidden
from import (a ``None`` entry in ``sys.modules`` makes an import fail) and adds a GPL engine to
the factory only when the config chooses it (:func:`add_engine`).
"""

from __future__ import annotations

import sys

import unified_planning.environment as up_environment
from unified_planning.environment import Environment

_GPL_PACKAGES = ("up_fast_downward", "up_pyperplan")


def planning_environment() -> Environment:
    """UP's global environment, made now if need be; credits quiet (``--json`` owns stdout)."""
    if up_environment.GLOBAL_ENVIRONMENT is None:
        hidden = [name for name in _GPL_PACKAGES if name not in sys.modules]
        for name in hidden:
            sys.modules[name] = None  # type: ignore[assignment]
        try:
            up_environment.GLOBAL_ENVIRONMENT = Environment()
        finally:
            for name in hidden:
                del sys.modules[name]
    env = up_environment.get_environment()
    env.credits_stream = None
    return env


def add_engine(env: Environment, name: str, module: str, class_name: str) -> None:
    """Make ``OneshotPlanner(name=name)`` find an engine (imported now)."""
    if name not in env.factory.engines:
        env.factory.add_engine(name, module, class_name)
