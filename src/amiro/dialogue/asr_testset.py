"""Speech test sets for ``amiro asr evaluate``: commands spoken by a synthesizer (espeak-ng),
clean or with white noise at a chosen SNR from a seeded generator, so the same files come
out on every run and machine."""

from __future__ import annotations

from collections.abc import Iterable
from importlib import resources
from pathlib import Path

import numpy as np

from amiro.core.config import ConfigError
from amiro.dialogue.audio import add_noise_at_snr, write_wav
from amiro.dialogue.tts import Synthesizer

SHIPPED_COMMANDS = Path(str(resources.files("amiro").joinpath("data/dialogue/grammar/asr_en.txt")))


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
