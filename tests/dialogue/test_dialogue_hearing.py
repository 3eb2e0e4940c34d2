"""How the simulated residents are heard: through audio by default, the text oracle when
asked, and the text oracle, said once in one line, when the speech stack is missing."""

from __future__ import annotations

import logging

import pytest

from amiro.core import registry
from amiro.core.messages import SpeechHeard
from amiro.dialogue.audio_loop import AudioLoopUnderstanding
from amiro.dialogue.config import AsrConfig, DialogueConfig
from amiro.dialogue.profiles import SpeakerProfile
from amiro.dialogue.stack import Dialogue, amiro_understanding
from amiro.dialogue.understanding import Nlu

MARIA = {"maria": SpeakerProfile(lang="fr")}


def test_the_default_hears_audio_and_the_oracle_is_named() -> None:
    nlu = Nlu()
    loop = amiro_understanding(nlu, DialogueConfig(), MARIA)
    assert isinstance(loop, AudioLoopUnderstanding)
    assert amiro_understanding(nlu, DialogueConfig(hearing="text-oracle"), MARIA) is nlu
    # a real recogniser's result (no oracle intent) is not voiced again
    assert loop.intent(SpeechHeard("oui", "fr", "maria"))[0] == "affirm"
    assert loop.heard == []
    # the simulator's reply is voiced, recognised in French, then understood
    assert loop.intent(SpeechHeard("oui, bien sûr", "fr", "maria", intent="affirm"))[0] == "affirm"
    ((said, recognised),) = loop.heard
    assert said == "oui, bien sûr" and "oui" in recognised.lower()
    # what a scenario's report names
    assert Dialogue(None, loop, None, None).hearing == "audio"  # type: ignore[arg-type]
    assert Dialogue(None, nlu, None, None).hearing == "text-oracle"  # type: ignore[arg-type]


def test_without_the_speech_extra_the_text_oracle_is_said_once(
    monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    monkeypatch.setattr(registry, "_REGISTRY", {k: dict(v) for k, v in registry._REGISTRY.items()})
    registry.register("asr", "absent", "amiro_no_such_speech_stack:make", extra="speech")
    nlu = Nlu()
    with caplog.at_level(logging.WARNING):
        understanding = amiro_understanding(
            nlu, DialogueConfig(asr=AsrConfig(backend="absent")), MARIA
        )
    assert understanding is nlu
    (record,) = [r for r in caplog.records if "hearing" in r.getMessage()]
    message = record.getMessage()
    assert "text oracle" in message and "amiro[speech]" in message and "\n" not in message
