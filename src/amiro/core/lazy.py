"""Package attributes loaded on first use, so importing a light subpackage stays light."""

from __future__ import annotations

import importlib
from collections.abc import Callable, Sequence
from typing import Any


def lazy_getattr(
    package: str, names: Sequence[str], submodules: Sequence[str]
) -> Callable[[str], Any]:
    """A module ``__getattr__`` (PEP 562) finding ``names`` in the package's ``submodules``."""

    def __getattr__(name: str) -> Any:  # noqa: N807 - the name PEP 562 looks for
        if name in names:
            for submodule in submodules:
                module = importlib.import_module(f"{package}.{submodule}")
                if hasattr(module, name):
                    return getattr(module, name)
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    return __getattr__
