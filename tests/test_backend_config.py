"""Backends are chosen by name through the registry: a config names only registered ones (a
one-line error naming the field and the choices), a plugin's backend is configured and built
like a shipped one, and a missing dependency names the extra to install."""

from __future__ import annotations

import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import yaml

from amiro.cli import main
from amiro.core import registry
from amiro.core.config import ConfigError, load
from amiro.dialogue.asr import ConfidenceGate
from amiro.dialogue.stack import make_recognizer, make_synthesizer
from amiro.perception.config import PerceptionConfig
from amiro.system import SystemConfig, build_system

FIELDS = [
    ("perception.backend", "camera, hri, oracle, sim"),
    ("perception.faces.backend", "dlib, sim"),
    ("perception.camera.detector", "hog, onnx"),
    ("navigation.localization", "amcl, oracle"),
    ("activity.backend", "camera-mediapipe, camera-onnx, onnx, oracle"),
    ("dialogue.asr.backend", "google, pocketsphinx, vosk, whisper"),
    ("dialogue.tts.backend", "espeak, google, piper"),
    ("dialogue.nlu", "amiro, oracle"),
]


def nested(dotted: str, value: object) -> dict[str, Any]:
    """``{"a": {"b": value}}`` for ``"a.b"``."""
    data: Any = value
    for key in reversed(dotted.split(".")):
        data = {key: data}
    return dict(data)


def write_config(path: Path, data: dict[str, Any]) -> Path:
    path.write_text(yaml.safe_dump(data), encoding="utf-8")
    return path


@pytest.fixture
def plugins(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    """A directory on ``sys.path`` for a plugin's modules; what the test registers is
    forgotten afterwards."""
    monkeypatch.setattr(registry, "_REGISTRY", {k: dict(v) for k, v in registry._REGISTRY.items()})
    monkeypatch.syspath_prepend(str(tmp_path))
    before = set(sys.modules)
    yield tmp_path
    for name in set(sys.modules) - before:
        if name.startswith("amiro_test_"):
            del sys.modules[name]


@pytest.mark.parametrize(("field", "choices"), FIELDS)
def test_an_unknown_backend_is_one_line_naming_the_field_and_the_choices(
    tmp_path: Path, field: str, choices: str, capsys: pytest.CaptureFixture[str]
) -> None:
    path = write_config(tmp_path / "bad.yaml", nested(field, "foo"))
    with pytest.raises(ConfigError) as info:
        load(SystemConfig, path)
    assert str(info.value) == f"{path}: {field}: unknown backend 'foo' (choices: {choices})"
    assert main(["serve", "--config", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert err == f"amiro: error: {info.value}"


@pytest.mark.parametrize(
    "kind", ["perception", "faces", "detector", "localization", "activity", "asr", "tts", "nlu"]
)
def test_every_shipped_backend_resolves_to_a_factory(kind: str) -> None:
    for name in registry.names(kind):
        assert callable(registry.resolve(kind, name)), f"{kind} {name}"


PLUGIN_FINDER = '''
from amiro.core.messages import Point
from amiro.perception.ports import SeenPerson


class StillFinder:
    """Sees Ana where the config's noise figure says, whatever the camera shows."""

    def __init__(self, inputs):
        self.inputs = inputs

    def look(self):
        x = self.inputs.cfg.position_noise_m
        return [SeenPerson("ana", Point(x, 2.0, 0.0), 0.9)]


def still_finder(inputs):
    return StillFinder(inputs)
'''


def test_a_plugins_people_finder_is_configured_and_built_by_name(
    plugins: Path, tmp_path: Path
) -> None:
    (plugins / "amiro_test_still_finder.py").write_text(PLUGIN_FINDER, encoding="utf-8")
    registry.register("perception", "still", "amiro_test_still_finder:still_finder")
    data = {"perception": {"backend": "still", "position_noise_m": 1.5}}
    cfg = load(SystemConfig, write_config(tmp_path / "plugin.yaml", data))
    system = build_system(cfg)
    try:
        finder = system.engine.modules.perception
        assert type(finder).__name__ == "StillFinder"
        (ana,) = finder.look()
        assert ana.name == "ana" and ana.position.x == 1.5
    finally:
        system.stop()


def test_a_plugins_recognizer_gets_the_asr_section_grammar_and_language(plugins: Path) -> None:
    (plugins / "amiro_test_echo_asr.py").write_text(
        "def echo(cfg, grammar, lang):\n    return (cfg.reject_below, grammar, lang)\n",
        encoding="utf-8",
    )
    registry.register("asr", "echo", "amiro_test_echo_asr:echo")
    cfg = SystemConfig.model_validate({"dialogue": {"asr": {"backend": "echo"}}}).dialogue
    recognizer = make_recognizer(cfg, grammar="answers", lang="fr")
    assert isinstance(recognizer, ConfidenceGate)
    assert recognizer.recognizer == (cfg.asr.reject_below, "answers", "fr")
    assert recognizer.reject_below == cfg.asr.listen_threshold


def test_a_missing_dependency_names_the_extra(plugins: Path) -> None:
    (plugins / "amiro_test_cloud_tts.py").write_text(
        "import amiro_missing_cloud_client\n\ndef cloud(cfg):\n    return None\n",
        encoding="utf-8",
    )
    registry.register("tts", "cloud", "amiro_test_cloud_tts:cloud", extra="voice")
    cfg = SystemConfig.model_validate({"dialogue": {"tts": {"backend": "cloud"}}}).dialogue
    with pytest.raises(ConfigError) as info:
        make_synthesizer(cfg)
    assert str(info.value) == (
        "tts backend 'cloud' needs the extra amiro[voice] "
        "(missing module: amiro_missing_cloud_client)"
    )


def test_dlib_faces_without_face_recognition_name_the_faces_extra(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setitem(sys.modules, "face_recognition", None)  # as if not installed
    cfg = PerceptionConfig.model_validate({"faces": {"backend": "dlib"}})
    with pytest.raises(ConfigError) as info:
        registry.create("faces", "dlib", cfg)
    assert str(info.value) == (
        "faces backend 'dlib' needs the extra amiro[faces] (missing module: face_recognition)"
    )
