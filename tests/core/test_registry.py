"""The registry of lazily imported backends."""

from __future__ import annotations

import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Annotated

import pytest
from pydantic import BaseModel, ValidationError

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


def test_missing_dependency_names_the_extra(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    (tmp_path / "amiro_test_voice_backend.py").write_text(
        "import amiro_missing_voice_dependency\n\nclass Engine:\n    pass\n"
    )
    (tmp_path / "amiro_test_lazy_voice.py").write_text(
        "def engine():\n    import amiro_missing_lazy_dependency\n"
    )
    monkeypatch.syspath_prepend(str(tmp_path))
    registry.register("asr", "heavy", "amiro_test_voice_backend:Engine", extra="voice")
    registry.register("asr", "lazy", "amiro_test_lazy_voice:engine", extra="voice")
    with pytest.raises(ConfigError) as info:
        registry.create("asr", "heavy")
    assert str(info.value) == (
        "asr backend 'heavy' needs the extra amiro[voice] "
        "(missing module: amiro_missing_voice_dependency)"
    )
    # a dependency the factory imports only when called is reported the same way
    with pytest.raises(ConfigError, match=r"needs the extra amiro\[voice\] \(missing module: "):
        registry.create("asr", "lazy")
    monkeypatch.delitem(sys.modules, "amiro_test_lazy_voice")


def test_a_package_registers_backends_through_its_entry_point(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    dist = tmp_path / "amiro_test_plugin-0.1.dist-info"
    dist.mkdir()
    (dist / "METADATA").write_text("Metadata-Version: 2.1\nName: amiro-test-plugin\nVersion: 0.1\n")
    (dist / "entry_points.txt").write_text("[amiro.backends]\nspeech = amiro_test_plugin\n")
    (tmp_path / "amiro_test_plugin.py").write_text(
        "from amiro.core.registry import register\n\n"
        'register("asr", "whisper", "amiro_test_plugin:Whisper")\n\n'
        "class Whisper:\n    pass\n"
    )
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setattr(registry, "_plugins_loaded", False)
    assert registry.names("asr") == ["whisper"]
    assert registry.resolve("asr", "whisper").__name__ == "Whisper"
    monkeypatch.delitem(sys.modules, "amiro_test_plugin")


def test_a_config_field_accepts_only_registered_names() -> None:
    class Section(BaseModel):
        backend: Annotated[str, registry.backend_name("asr")] = "sphinx"

    registry.register("asr", "sphinx", "nowhere:Y")
    registry.register("asr", "whisper", "nowhere:X")
    assert Section(backend="whisper").backend == "whisper"
    with pytest.raises(ValidationError) as info:
        Section(backend="vosk")
    assert info.value.errors()[0]["msg"] == "unknown backend 'vosk' (choices: sphinx, whisper)"
