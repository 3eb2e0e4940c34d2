"""Real audio: espeak-ng speaks, sox adds noise, pocketsphinx recognises (grammar mode)."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import numpy as np
import pytest

from amiro.core.config import ConfigError
from amiro.dialogue.asr_eval import evaluate_asr, reference
from amiro.dialogue.asr_pocketsphinx import PocketsphinxRecognizer
from amiro.dialogue.audio import Audio, read_wav, resample, write_wav
from amiro.dialogue.config import AsrConfig, DialogueConfig, TtsConfig
from amiro.dialogue.stack import make_recognizer, make_synthesizer
from amiro.dialogue.tts import EspeakSynthesizer
from amiro.dialogue.vad import utterances

COMMANDS = (
    "display my blood pressure",
    "what plans do i have for tomorrow",
    "turn on the lights in the kitchen",
    "how will the weather be tomorrow",
)


@pytest.fixture(scope="module")
def espeak() -> EspeakSynthesizer:
    return EspeakSynthesizer()


@pytest.fixture(scope="module")
def recordings(tmp_path_factory: pytest.TempPathFactory, espeak: EspeakSynthesizer) -> Path:
    """Clean and noisy (sox white noise at about 20 dB SNR) recordings named by transcript."""
    base = tmp_path_factory.mktemp("asr")
    clean, noisy = base / "clean", base / "noisy"
    clean.mkdir()
    noisy.mkdir()
    for text in COMMANDS:
        name = text.replace(" ", "_") + ".wav"
        write_wav(clean / name, espeak.synthesize(text, "en", "en-us", 140))
        # -R: sox's repeatable mode, so the noise (and the test) is the same on every run
        noise = f"|sox -R {clean / name} -p synth whitenoise vol 0.02"
        subprocess.run(
            ["sox", "-R", "-m", str(clean / name), noise, str(noisy / name)], check=True
        )
    return clean


@pytest.mark.parametrize("which", ["clean", "noisy"])
def test_grammar_mode_recognises_commands(recordings: Path, which: str) -> None:
    report = evaluate_asr(recordings.parent / which, PocketsphinxRecognizer("nlu"))
    assert report["files"] == len(COMMANDS)
    assert report["sentence_accuracy"] >= 0.75
    assert report["wer"] <= 0.15
    assert report["rtf"] > 0.0


def test_language_model_mode_is_worse(recordings: Path) -> None:
    grammar = evaluate_asr(recordings, PocketsphinxRecognizer("nlu"))
    free = evaluate_asr(recordings, PocketsphinxRecognizer("none"))
    assert free["wer"] > grammar["wer"]


def test_answers_grammar_for_listen(espeak: EspeakSynthesizer) -> None:
    recognizer = PocketsphinxRecognizer("answers")
    assert recognizer.transcribe(espeak.synthesize("yes please", "en")).text == "yes please"
    assert recognizer.transcribe(espeak.synthesize("no thank you", "en")).text == "no thank you"


def test_tts_speaks_every_language(espeak: EspeakSynthesizer) -> None:
    for lang, text in (("en", "hello"), ("ro", "bună ziua"), ("fr", "bonjour")):
        audio = espeak.synthesize(text, lang)
        assert audio.seconds > 0.3
        assert np.abs(audio.samples).max() > 1000


def test_wav_round_trip_and_resampling(tmp_path: Path) -> None:
    tone = Audio((1000 * np.sin(np.arange(22050) / 10.0)).astype(np.int16), 22050)
    write_wav(tmp_path / "t.wav", tone)
    back = read_wav(tmp_path / "t.wav")
    assert back.rate == 22050 and np.array_equal(back.samples, tone.samples)
    assert len(resample(back).samples) == 16000


def test_utterances_split_at_silence(espeak: EspeakSynthesizer) -> None:
    a, b = (resample(espeak.synthesize(t, "en")) for t in ("hello there", "turn on the lights"))
    gap = np.zeros(16000, np.int16)
    stream = Audio(np.concatenate([gap, a.samples, gap, gap, b.samples, gap]), 16000)
    found = list(utterances(stream))
    assert len(found) == 2
    assert abs(found[1].seconds - b.seconds) < 0.5


def test_reference_from_name_or_sidecar(tmp_path: Path) -> None:
    (tmp_path / "x.txt").write_text("Turn ON the lights", encoding="utf-8")
    assert reference(tmp_path / "x.wav") == "turn on the lights"
    assert reference(tmp_path / "go_to_maria.wav") == "go to maria"


def test_clear_errors() -> None:
    with pytest.raises(ConfigError, match="not a Vosk model"):
        make_recognizer(DialogueConfig(asr=AsrConfig(backend="vosk", vosk_model=Path("/nope"))))
    with pytest.raises(ConfigError, match="voice file not found"):
        make_synthesizer(DialogueConfig(tts=TtsConfig(backend="piper")))
    with pytest.raises(ConfigError, match="English"):
        PocketsphinxRecognizer("nlu", lang="ro")
    with pytest.raises(ConfigError, match="no such directory"):
        evaluate_asr(Path("/nope"), PocketsphinxRecognizer("answers"))


def test_cli_asr_evaluate(recordings: Path, capsys: pytest.CaptureFixture[str]) -> None:
    import argparse

    from amiro.dialogue.cli import register

    parser = argparse.ArgumentParser()
    register(parser.add_subparsers())
    args = parser.parse_args(["asr", "evaluate", str(recordings), "--json"])
    assert args.handler(args) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["files"] == len(COMMANDS) and {"wer", "sentence_accuracy", "rtf"} <= set(out)
