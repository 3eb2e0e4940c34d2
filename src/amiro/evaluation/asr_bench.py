"""``amiro asr bench``: the cost of hearing on this machine.  First load (the packaged
weights joined if needed, then read by CTranslate2) and the real-time factor (decode time /
audio time) of Whisper on commands of about 5 s, spoken by espeak-ng from amiro's held-out
utterances in each language (generated speech: only the speed is measured here).  Wall time
is read only here, to measure speed."""

from __future__ import annotations

import json
import statistics
from typing import Any

from amiro.core.clock import wall_seconds
from amiro.dialogue.asr_prompt import prompt_for
from amiro.dialogue.asr_whisper import WhisperRecognizer
from amiro.dialogue.audio import Audio
from amiro.dialogue.config import AsrConfig
from amiro.dialogue.nlu_eval import shipped_eval_files
from amiro.dialogue.tts import EspeakSynthesizer
from amiro.dialogue.whisper_model import load_whisper, packaged_model

LANGS = ("en", "fr", "ro")
COMMAND_S = 5.0


def commands(lang: str, count: int, synthesizer: EspeakSynthesizer) -> list[Audio]:
    """``count`` utterances of at least :data:`COMMAND_S` s: held-out requests joined."""
    path = next(p for p in shipped_eval_files() if p.stem == lang)
    texts = [json.loads(line)["text"] for line in path.read_text("utf-8").splitlines() if line]
    out: list[Audio] = []
    joined: list[str] = []
    for text in texts:
        joined.append(text)
        audio = synthesizer.synthesize(", ".join(joined), lang)
        if audio.seconds >= COMMAND_S:
            out.append(audio)
            joined = []
        if len(out) == count:
            break
    return out


def bench(repeats: int = 5, cfg: AsrConfig | None = None) -> dict[str, Any]:
    cfg = cfg or AsrConfig()
    started = wall_seconds()
    path = cfg.whisper_model or packaged_model()
    joined_s = wall_seconds() - started
    started = wall_seconds()
    model = load_whisper(path, cfg.whisper_threads, cfg.whisper_compute_type)
    load_s = wall_seconds() - started
    synthesizer = EspeakSynthesizer()
    rtf: dict[str, dict[str, float]] = {}
    for lang in LANGS:
        recognizer = WhisperRecognizer(model, lang, prompt_for("nlu", lang), cfg.whisper_beam_size)
        ratios = []
        for audio in commands(lang, repeats, synthesizer):
            started = wall_seconds()
            recognizer.transcribe(audio)
            ratios.append((wall_seconds() - started) / audio.seconds)
        rtf[lang] = {"median": statistics.median(ratios), "max": max(ratios), "n": len(ratios)}
    return {
        "model": str(path),
        "threads": cfg.whisper_threads,
        "compute_type": cfg.whisper_compute_type,
        "beam_size": cfg.whisper_beam_size,
        "join_or_check_s": joined_s,
        "first_load_s": load_s,
        "command_s": COMMAND_S,
        "rtf": rtf,
    }
