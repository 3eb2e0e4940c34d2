"""``amiro asr evaluate``: word error rate, sentence accuracy and real-time factor over WAV
files whose transcript is the file name (``_`` between words) or a sidecar ``.txt``."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import jiwer

from amiro.core.config import ConfigError
from amiro.dialogue.asr import Recognizer
from amiro.dialogue.audio import read_wav
from amiro.dialogue.text import normalize


def reference(wav: Path) -> str:
    sidecar = wav.with_suffix(".txt")
    text = sidecar.read_text(encoding="utf-8") if sidecar.is_file() else wav.stem.replace("_", " ")
    return normalize(text)


def evaluate_asr(directory: Path, recognizer: Recognizer) -> dict[str, Any]:
    if not directory.is_dir():
        raise ConfigError(f"{directory}: no such directory")
    wavs = sorted(directory.glob("*.wav"))
    if not wavs:
        raise ConfigError(f"{directory}: no .wav files")
    refs, hyps, rows = [], [], []
    audio_s = decode_s = 0.0
    for wav in wavs:
        audio = read_wav(wav)
        start = time.perf_counter()
        hyp = normalize(recognizer.transcribe(audio).text)
        decode_s += time.perf_counter() - start
        audio_s += audio.seconds
        refs.append(reference(wav))
        hyps.append(hyp)
        rows.append({"file": wav.name, "reference": refs[-1], "hypothesis": hyp})
    return {
        "files": len(wavs),
        "wer": jiwer.wer(refs, [h or "<empty>" for h in hyps]),
        "sentence_accuracy": sum(r == h for r, h in zip(refs, hyps, strict=True)) / len(wavs),
        "rtf": decode_s / audio_s if audio_s else 0.0,
        "results": rows,
    }
