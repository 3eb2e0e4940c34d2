"""One registry of named backends, so configuration picks an adapter by name.

Adapters register a lazy ``"module:attribute"`` target; the module (and its heavy optional
dependency: onnxruntime, pocketsphinx, rclpy ...) is imported only when that backend is used.
"""

from __future__ import annotations

import importlib
from typing import Any

from amiro.core.config import ConfigError

_REGISTRY: dict[str, dict[str, str]] = {}


def register(kind: str, name: str, target: str) -> None:
    """Declare that backend ``name`` of ``kind`` lives at ``target`` ("pkg.module:Class")."""
    _REGISTRY.setdefault(kind, {})[name] = target


def names(kind: str) -> list[str]:
    return sorted(_REGISTRY.get(kind, {}))


def resolve(kind: str, name: str) -> Any:
    targets = _REGISTRY.get(kind, {})
    if name not in targets:
        choices = ", ".join(names(kind)) or "none registered"
        raise ConfigError(f"unknown {kind} backend '{name}' (choices: {choices})")
    module_name, _, attr = targets[name].partition(":")
    try:
        module = importlib.import_module(module_name)
    except ImportError as exc:
        raise ConfigError(
            f"{kind} backend '{name}' needs a package that is not installed: {exc.name}"
        ) from None
    try:
        return getattr(module, attr)
    except AttributeError:
        raise ConfigError(f"{kind} backend '{name}': {module_name} has no {attr}") from None


def create(kind: str, name: str, **kwargs: Any) -> Any:
    return resolve(kind, name)(**kwargs)
