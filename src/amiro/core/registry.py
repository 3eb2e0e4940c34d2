"""One registry of named backends, so configuration picks an adapter by name.

Adapters register a lazy ``"module:attribute"`` target; the module (and its heavy optional
dependency: onnxruntime, pocketsphinx, rclpy ...) is imported only when that backend is used.
Each entry names the extra (``pip install 'amiro[extra]'``) its dependencies come from, None
for the core install, so a missing module is a one-line error saying what to install.

Config fields that name a backend are plain strings checked against this registry when the
config loads (:func:`backend_name`), so a plugin's backend is configured like a shipped one: a
third-party package calls :func:`register` once, in a module its user imports or that it lists
in the ``amiro.backends`` entry-point group (loaded before the first lookup).  Each capability
registers its own backends in its ``backends`` module, which its config module imports.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from importlib.metadata import entry_points
from typing import Any

from pydantic import AfterValidator
from pydantic_core import PydanticCustomError

from amiro.core.config import ConfigError

PLUGIN_GROUP = "amiro.backends"


@dataclass(frozen=True)
class Backend:
    target: str  # "pkg.module:attribute"
    extra: str | None = None  # the amiro extra its dependencies come from; None: core


_REGISTRY: dict[str, dict[str, Backend]] = {}
_plugins_loaded = False


def register(kind: str, name: str, target: str, extra: str | None = None) -> None:
    """Declare that backend ``name`` of ``kind`` lives at ``target`` ("pkg.module:Class"),
    its optional dependencies coming with ``amiro[extra]``."""
    _REGISTRY.setdefault(kind, {})[name] = Backend(target, extra)


def load_plugins() -> None:
    """Import, once, each module listed in the ``amiro.backends`` entry-point group: each
    registers its backends."""
    global _plugins_loaded
    if _plugins_loaded:
        return
    _plugins_loaded = True
    for point in entry_points(group=PLUGIN_GROUP):
        try:
            point.load()
        except Exception as exc:
            raise ConfigError(
                f"backend plugin {point.name} ({point.value}) failed to load: {exc}"
            ) from None


def _backends(kind: str) -> dict[str, Backend]:
    load_plugins()
    return _REGISTRY.get(kind, {})


def names(kind: str) -> list[str]:
    return sorted(_backends(kind))


def _entry(kind: str, name: str) -> Backend:
    backends = _backends(kind)
    if name not in backends:
        choices = ", ".join(names(kind)) or "none registered"
        raise ConfigError(f"unknown {kind} backend '{name}' (choices: {choices})")
    return backends[name]


def _missing(kind: str, name: str, entry: Backend, exc: ImportError) -> ConfigError:
    module = exc.name or str(exc)
    if entry.extra is None:
        return ConfigError(
            f"{kind} backend '{name}' needs a package that is not installed: {module}"
        )
    return ConfigError(
        f"{kind} backend '{name}' needs the extra amiro[{entry.extra}] (missing module: {module})"
    )


def resolve(kind: str, name: str) -> Any:
    entry = _entry(kind, name)
    module_name, _, attr = entry.target.partition(":")
    try:
        module = importlib.import_module(module_name)
    except ImportError as exc:
        raise _missing(kind, name, entry, exc) from None
    try:
        return getattr(module, attr)
    except AttributeError:
        raise ConfigError(f"{kind} backend '{name}': {module_name} has no {attr}") from None


def create(kind: str, name: str, *args: Any, **kwargs: Any) -> Any:
    """The backend built by its factory; a module the factory imports and cannot find is
    reported as the backend's missing dependency."""
    factory = resolve(kind, name)
    try:
        return factory(*args, **kwargs)
    except ModuleNotFoundError as exc:
        raise _missing(kind, name, _entry(kind, name), exc) from None


def backend_name(kind: str) -> AfterValidator:
    """A config field's validator: the name of a registered backend of ``kind``, else the
    one-line error ``unknown backend 'foo' (choices: a, b)``."""

    def check(name: str) -> str:
        if name not in _backends(kind):
            raise PydanticCustomError(
                "unknown_backend",
                "unknown backend '{name}' (choices: {choices})",
                {"name": name, "choices": ", ".join(names(kind)) or "none registered"},
            )
        return name

    return AfterValidator(check)
