"""The grammar-mode confidence and the rejection gate, on hand-made decoder paths."""

from __future__ import annotations

import numpy as np
import pytest

from amiro.core.config import ConfigError, parse
from amiro.dialogue.asr import ConfidenceGate, Transcript, gate
from amiro.dialogue.asr_confidence import (
    GAP_LIMIT,
    UNEXPLAINED_LIMIT,
    GrammarFit,
    Segment,
    grammar_fit,
)
from amiro.dialogue.audio import Audio
from amiro.dialogue.config import DialogueConfig

# 100 frames: silence, two words (frames 10-49 and 50-89), silence
PHONES = [
    Segment("SIL", 0, 9, -100),
    Segment("HH", 10, 29, -2000),
    Segment("AH", 30, 49, -2000),
    Segment("L", 50, 89, -4000),
    Segment("SIL", 90, 99, -100),
]


def test_words_that_fit_as_well_as_the_phone_loop_are_confident() -> None:
    grammar = [
        Segment("<sil>", 0, 9, -100),
        Segment("(NULL)", -1, -1, 0),
        Segment("hello", 10, 49, -4000),
        Segment("there", 50, 89, -4000),
        Segment("<sil>", 90, 99, -100),
    ]
    fit = grammar_fit(grammar, PHONES, 100)
    assert fit.unexplained == 0.0 and fit.gap == 0.0
    assert fit.confidence() == 1.0


def test_speech_hidden_in_silence_is_unexplained() -> None:
    """The grammar explains the first word and spends the second one in silence."""
    grammar = [
        Segment("<sil>", 0, 9, -100),
        Segment("hello", 10, 49, -4000),
        Segment("<sil>", 50, 99, -4500),
    ]
    fit = grammar_fit(grammar, PHONES, 100)
    assert fit.unexplained == pytest.approx(0.5)  # 40 of the 80 speech frames
    assert fit.confidence() == 0.0


def test_words_forced_onto_other_sounds_have_a_gap() -> None:
    gap = 0.5 * GAP_LIMIT  # per frame, over the 80 word frames
    grammar = [
        Segment("<sil>", 0, 9, -100),
        Segment("hello", 10, 49, int(-4000 - 40 * gap)),
        Segment("there", 50, 89, int(-4000 - 40 * gap)),
        Segment("<sil>", 90, 99, -100),
    ]
    fit = grammar_fit(grammar, PHONES, 100)
    assert fit.gap == pytest.approx(gap)
    assert fit.confidence() == pytest.approx(0.75)


def test_confidence_is_one_half_at_either_limit() -> None:
    assert GrammarFit(UNEXPLAINED_LIMIT, 0.0).confidence() == pytest.approx(0.5)
    assert GrammarFit(0.0, GAP_LIMIT).confidence() == pytest.approx(0.5)
    assert GrammarFit(UNEXPLAINED_LIMIT, 1.5 * GAP_LIMIT).confidence() == pytest.approx(0.25)


def test_a_path_without_words_has_no_confidence() -> None:
    assert grammar_fit([Segment("<sil>", 0, 99, -100)], PHONES, 100).confidence() == 0.0


def test_gate_rejects_below_the_threshold_and_keeps_the_guess() -> None:
    rejected = gate(Transcript("go to maria", 0.3), 0.5)
    assert rejected == Transcript("", 0.3, rejected="go to maria")
    assert rejected.guess == "go to maria"
    assert gate(Transcript("go to maria", 0.5), 0.5).text == "go to maria"
    assert gate(Transcript("", 0.0), 0.5) == Transcript("", 0.0)


def test_confidence_gate_wraps_any_recognizer() -> None:
    class Fixed:
        def transcribe(self, audio: Audio) -> Transcript:
            return Transcript("yes", 0.4)

    audio = Audio(np.zeros(160, np.int16), 16000)
    assert ConfidenceGate(Fixed(), 0.5).transcribe(audio).text == ""
    assert ConfidenceGate(Fixed(), 0.3).transcribe(audio).text == "yes"


@pytest.mark.parametrize("key", ["reject_below", "listen_reject_below"])
def test_thresholds_are_validated(key: str) -> None:
    cfg = parse(DialogueConfig, {"asr": {key: 0.7}}, "cfg")
    assert getattr(cfg.asr, key) == 0.7
    with pytest.raises(ConfigError, match=f"asr.{key}"):
        parse(DialogueConfig, {"asr": {key: 1.5}}, "cfg")
    with pytest.raises(ConfigError, match=f"asr.{key}"):
        parse(DialogueConfig, {"asr": {key: "high"}}, "cfg")
