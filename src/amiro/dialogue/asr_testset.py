"""Speech test sets for ``amiro asr evaluate``: commands spoken by a synthesizer (espeak-ng),
clean or with white noise at a chosen SNR, and noise-only clips for the rejection test, all
from a seeded generator, so the same files come out on every run and machine."""

from __future__ import annotations

from collections.abc import Iterable
from importlib import resources
from pathlib import Path

import numpy as np

from amiro.core.config import ConfigError
from amiro.dialogue.audio import ASR_RATE, Audio, add_noise_at_snr, write_wav
from amiro.dialogue.tts import Synthesizer

_GRAMMAR_DIR = resources.files("amiro").joinpath("data/dialogue/grammar")
SHIPPED_COMMANDS = Path(str(_GRAMMAR_DIR.joinpath("asr_en.txt")))
SHIPPED_OUT_OF_GRAMMAR = Path(str(_GRAMMAR_DIR.joinpath("asr_en_oog.txt")))


def read_commands(path: Path) -> list[str]:
    """One command per line; blank lines and ``#`` comments are skipped."""
    if not path.is_file():
        raise ConfigError(f"{path}: no such file")
    lines = (line.strip() for line in path.read_text(encoding="utf-8").splitlines())
    commands = [line for line in lines if line and not line.startswith("#")]
    if not commands:
        raise ConfigError(f"{path}: no commands")
    return commands


def file_name(command: str) -> str:
    """The WAV name that ``asr_eval.reference`` reads the transcript back from."""
    return "_".join(command.split()) + ".wav"


def write_test_set(
    commands: Iterable[str],
    out: Path,
    synthesizer: Synthesizer,
    rng: np.random.Generator,
    snr_db: float | None = None,
    words_per_minute: int = 140,
) -> list[Path]:
    written = []
    for command in commands:
        audio = synthesizer.synthesize(command, "en", "", words_per_minute)
        if snr_db is not None:
            audio = add_noise_at_snr(audio, rng, snr_db)
        written.append(out / file_name(command))
        write_wav(written[-1], audio)
    return written


def noise_clip(rng: np.random.Generator) -> Audio:
    """1-3 s of white or brown noise, from about -60 to -20 dBFS RMS: a fan, rustling, traffic,
    which the recogniser must not take for a command."""
    samples = int(ASR_RATE * rng.uniform(1.0, 3.0))
    x = rng.normal(0.0, 1.0, samples)
    if rng.random() < 0.5:
        x = np.cumsum(x)
        x -= np.linspace(x[0], x[-1], samples)  # no drift: the level stays where it is set
    x *= 10.0 ** rng.uniform(1.5, 3.5) / max(float(np.std(x)), 1e-9)
    return Audio(np.clip(np.round(x), -32768, 32767).astype(np.int16), ASR_RATE)


def write_noise_clips(count: int, out: Path, rng: np.random.Generator) -> list[Path]:
    written = [out / f"noise_{i:02d}.wav" for i in range(count)]
    for path in written:
        write_wav(path, noise_clip(rng))
    return written
