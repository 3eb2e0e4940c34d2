"""The audio front end: any WAV read as 16-bit mono; Silero VAD (the model in the
faster-whisper wheel): streaming gives the same speech probabilities as the whole recording,
and the endpointer cuts utterances at pauses."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from scipy.io import wavfile

from amiro.dialogue.audio import ASR_RATE, Audio, read_wav, resample
from amiro.dialogue.silero import WINDOW, SileroVad, as_float, speech_span, utterances
from amiro.dialogue.tts import EspeakSynthesizer


@pytest.fixture(scope="module")
def two_commands() -> tuple[Audio, Audio, Audio]:
    """Two spoken commands with 1.5 s of silence between them, and each alone."""
    espeak = EspeakSynthesizer()
    first = espeak.synthesize("go to the kitchen", "en")
    second = espeak.synthesize("what is the weather tomorrow", "en")
    first, second = resample(first, ASR_RATE), resample(second, ASR_RATE)
    pause = np.zeros(int(1.5 * ASR_RATE), np.int16)
    both = np.concatenate([pause, first.samples, pause, second.samples, pause])
    return Audio(both, ASR_RATE), first, second


def test_streaming_matches_the_whole_recording(two_commands: tuple[Audio, Audio, Audio]) -> None:
    x = as_float(two_commands[0])
    x = x[: len(x) // WINDOW * WINDOW]
    whole = SileroVad().probs(x)
    vad = SileroVad()
    streamed = np.concatenate([vad.probs(x[i : i + 1000]) for i in range(0, len(x), 1000)])
    assert len(streamed) == len(whole) == len(x) // WINDOW
    np.testing.assert_allclose(streamed, whole, atol=1e-4)


def test_endpointer_finds_each_utterance(two_commands: tuple[Audio, Audio, Audio]) -> None:
    both, first, second = two_commands
    chunks = [
        Audio(both.samples[i : i + 1600], ASR_RATE) for i in range(0, len(both.samples), 1600)
    ]
    found = list(utterances(chunks))
    assert len(found) == 2
    for got, said in zip(found, (first, second), strict=True):
        assert abs(got.seconds - said.seconds) < 0.8  # trimmed silence, kept a little pad


def test_no_speech_span_in_silence_or_hum() -> None:
    t = np.arange(2 * ASR_RATE) / ASR_RATE
    hum = (3000 * np.sin(2 * np.pi * 50 * t)).astype(np.int16)
    assert speech_span(Audio(np.zeros(ASR_RATE, np.int16), ASR_RATE)) is None
    assert speech_span(Audio(hum, ASR_RATE)) is None


@pytest.mark.parametrize("kind", ["float32", "int32", "uint8", "int16"])
def test_any_pcm_or_float_wav_reads_as_16_bit_mono(tmp_path: Path, kind: str) -> None:
    rng = np.random.default_rng(0)
    mono = (8000 * np.sin(np.linspace(0, 200, 44100)) + rng.normal(0, 50, 44100)).astype(np.int16)
    stereo = np.stack([mono, mono], axis=1).astype(np.float64) / 32768.0
    data = {
        "float32": stereo.astype(np.float32),
        "int32": (stereo * 2**31).astype(np.int32),
        "uint8": np.clip(np.round(stereo * 128 + 128), 0, 255).astype(np.uint8),
        "int16": (stereo * 32768).astype(np.int16),
    }[kind]
    wavfile.write(tmp_path / "x.wav", 44100, data)
    audio = read_wav(tmp_path / "x.wav")
    assert audio.rate == 44100 and audio.samples.dtype == np.int16 and audio.samples.ndim == 1
    tolerance = 130 if kind == "uint8" else 2  # 8 bits: steps of 256
    assert np.abs(audio.samples.astype(int) - mono.astype(int)).max() <= tolerance
    assert resample(audio).rate == ASR_RATE
