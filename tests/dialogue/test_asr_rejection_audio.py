"""Rejection on real audio: espeak-ng speaks, pocketsphinx recognises with the command
grammar and its phone-loop confidence; out-of-grammar speech and noise are not understood."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np
import pytest

from amiro.commands.dialogue import register
from amiro.core.config import ConfigError
from amiro.dialogue.actions import Actions
from amiro.dialogue.asr import DEFAULT_REJECT_BELOW, ConfidenceGate, gate
from amiro.dialogue.asr_pocketsphinx import PocketsphinxRecognizer
from amiro.dialogue.asr_testset import (
    SHIPPED_OUT_OF_GRAMMAR,
    noise_clip,
    read_commands,
    write_noise_clips,
    write_test_set,
)
from amiro.dialogue.config import AsrConfig, DialogueConfig
from amiro.dialogue.domain import shipped_domain
from amiro.dialogue.manager import DialogueManager
from amiro.dialogue.phrases import phrase
from amiro.dialogue.sources import offline_sources
from amiro.dialogue.stack import make_recognizer
from amiro.dialogue.tts import EspeakSynthesizer
from amiro.dialogue.understanding import Nlu

# held-out lines of the out-of-grammar set (not used to tune the limits) and commands
OUT_OF_GRAMMAR = ("the kettle is making a strange noise", "did anybody phone while i was asleep")
COMMANDS = ("show my blood pressure", "what plans do i have for today")


@pytest.fixture(scope="module")
def espeak() -> EspeakSynthesizer:
    return EspeakSynthesizer()


@pytest.fixture(scope="module")
def recognizer() -> PocketsphinxRecognizer:
    return PocketsphinxRecognizer("nlu")


@pytest.mark.parametrize("sentence", OUT_OF_GRAMMAR)
def test_out_of_grammar_speech_is_rejected(
    sentence: str, espeak: EspeakSynthesizer, recognizer: PocketsphinxRecognizer
) -> None:
    heard = recognizer.transcribe(espeak.synthesize(sentence, "en"))
    assert heard.text, "grammar mode always finds some sentence"
    assert heard.confidence < DEFAULT_REJECT_BELOW
    assert gate(heard, DEFAULT_REJECT_BELOW).text == ""


@pytest.mark.parametrize("command", COMMANDS)
def test_in_grammar_commands_are_accepted_with_their_text(
    command: str, espeak: EspeakSynthesizer, recognizer: PocketsphinxRecognizer
) -> None:
    heard = gate(recognizer.transcribe(espeak.synthesize(command, "en")), DEFAULT_REJECT_BELOW)
    assert heard.text == command
    assert heard.confidence >= DEFAULT_REJECT_BELOW


def test_noise_is_not_a_command(recognizer: PocketsphinxRecognizer) -> None:
    clip = noise_clip(np.random.default_rng(3))
    assert gate(recognizer.transcribe(clip), DEFAULT_REJECT_BELOW).text == ""


def test_the_configured_recognizer_rejects_and_the_manager_says_so(
    espeak: EspeakSynthesizer,
) -> None:
    """Through ``make_recognizer`` (the config's threshold) to the dialogue manager."""
    asr = make_recognizer(DialogueConfig(asr=AsrConfig(backend="pocketsphinx")))
    heard = asr.transcribe(espeak.synthesize(OUT_OF_GRAMMAR[0], "en"))
    assert heard.text == "" and heard.rejected
    manager = DialogueManager(Nlu(), shipped_domain(), Actions(offline_sources()))
    assert manager.handle(heard.text, "en").text == phrase("utter_not_understood", "en")


def test_listen_answers_have_their_own_threshold() -> None:
    cfg = DialogueConfig(asr=AsrConfig(reject_below=0.6, listen_reject_below=0.3))
    answers = make_recognizer(cfg, grammar="answers")
    assert isinstance(answers, ConfidenceGate) and answers.reject_below == 0.3
    # pocketsphinx's Listen rejects nothing by default
    assert AsrConfig(backend="pocketsphinx").listen_threshold == 0.0


def test_out_of_grammar_set_is_outside_the_grammar(recognizer: PocketsphinxRecognizer) -> None:
    sentences = read_commands(SHIPPED_OUT_OF_GRAMMAR)
    assert len(sentences) == 50
    grammar = recognizer.decoder.get_fsg("nlu")
    assert [s for s in sentences if grammar.accept(s)] == []
    assert grammar.accept(COMMANDS[0])  # the check can say yes


def test_noise_clips_are_seeded(tmp_path: Path) -> None:
    first = write_noise_clips(2, tmp_path / "a", np.random.default_rng(7))
    second = write_noise_clips(2, tmp_path / "b", np.random.default_rng(7))
    assert [p.name for p in first] == ["noise_00.wav", "noise_01.wav"]
    assert [p.read_bytes() for p in first] == [p.read_bytes() for p in second]


def _cli(argv: list[str]) -> int:
    parser = argparse.ArgumentParser()
    register(parser.add_subparsers())
    args = parser.parse_args(argv)
    code: int = args.handler(args)
    return code


def test_cli_reports_false_acceptance_and_rejection(
    tmp_path: Path, espeak: EspeakSynthesizer, capsys: pytest.CaptureFixture[str]
) -> None:
    write_test_set(COMMANDS, tmp_path / "in", espeak, np.random.default_rng(0))
    write_test_set(OUT_OF_GRAMMAR, tmp_path / "oog", espeak, np.random.default_rng(0))
    write_noise_clips(1, tmp_path / "oog", np.random.default_rng(0))
    argv = ["asr", "evaluate", str(tmp_path / "in"), "--out-of-grammar", str(tmp_path / "oog")]
    argv += ["--backend", "pocketsphinx"]
    assert _cli([*argv, "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["files"] == 2 and report["sentence_accuracy"] == 1.0  # the contract keys
    assert {"wer", "rtf"} <= set(report)
    assert report["out_of_grammar_files"] == 3
    assert report["false_acceptance_rate"] == 0.0
    assert report["false_rejection_rate"] == 0.0
    no_rejection = report["roc"][0]
    assert no_rejection["threshold"] == 0.0 and no_rejection["false_acceptance_rate"] > 0.0
    with pytest.raises(ConfigError, match="between 0 and 1"):
        _cli([*argv, "--reject-below", "2"])
