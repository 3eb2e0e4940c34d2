"""The registry of lazily imported backends."""

from __future__ import annotations

import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from amiro.core import registry
from amiro.core.clock import SimClock
from amiro.core.config import ConfigError


@pytest.fixture(autouse=True)
def fresh_registry(monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    monkeypatch.setattr(registry, "_REGISTRY", {})
    yield


def test_register_resolve_create() -> None:
    registry.register("clock", "sim", "amiro.core.clock:SimClock")
    registry.register("clock", "another", "amiro.core.clock:SimClock")
    assert registry.names("clock") == ["another", "sim"]
    assert registry.resolve("clock", "sim") is SimClock
    clock = registry.create("clock", "sim", speed=2.0, start=5.0)
    assert isinstance(clock, SimClock)
    assert clock.speed == 2.0
    assert clock.now() == 5.0


def test_target_is_imported_only_when_used(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    (tmp_path / "amiro_test_lazy_backend.py").write_text(
        "class Engine:\n    def __init__(self, gain=1):\n        self.gain = gain\n"
    )
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.delitem(sys.modules, "amiro_test_lazy_backend", raising=False)
    registry.register("engine", "lazy", "amiro_test_lazy_backend:Engine")
    assert "amiro_test_lazy_backend" not in sys.modules
    engine = registry.create("engine", "lazy", gain=3)
    assert "amiro_test_lazy_backend" in sys.modules
    assert engine.gain == 3
    monkeypatch.delitem(sys.modules, "amiro_test_lazy_backend")


def test_unknown_name_lists_choices() -> None:
    registry.register("asr", "whisper", "nowhere:X")
    registry.register("asr", "sphinx", "nowhere:Y")
    with pytest.raises(
        ConfigError, match=r"unknown asr backend 'vosk' \(choices: sphinx, whisper\)"
    ):
        registry.resolve("asr", "vosk")
    with pytest.raises(ConfigError, match="none registered"):
        registry.create("tts", "any")


def test_missing_package_is_named() -> None:
    registry.register("asr", "sphinx", "amiro_surely_not_installed.engine:Engine")
    with pytest.raises(ConfigError) as info:
        registry.create("asr", "sphinx")
    message = str(info.value)
    assert "not installed" in message
    assert "amiro_surely_not_installed" in message
    assert "sphinx" in message


def test_missing_dependency_of_installed_module_is_named(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    (tmp_path / "amiro_test_heavy_backend.py").write_text(
        "import amiro_missing_heavy_dependency\n\nclass Engine:\n    pass\n"
    )
    monkeypatch.syspath_prepend(str(tmp_path))
    registry.register("vision", "heavy", "amiro_test_heavy_backend:Engine")
    with pytest.raises(ConfigError, match="not installed: amiro_missing_heavy_dependency"):
        registry.resolve("vision", "heavy")
    assert "amiro_test_heavy_backend" not in sys.modules
