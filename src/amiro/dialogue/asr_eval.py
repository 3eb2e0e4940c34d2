"""``amiro asr evaluate``: word error rate, sentence accuracy and real-time factor over WAV
files whose transcript is the file name (``_`` between words) or a sidecar ``.txt``; with
out-of-grammar recordings, how well low-confidence results are rejected.  Transcripts are
compared after :func:`amiro.dialogue.spoken_numbers.wer_normalize` (case, punctuation,
diacritics, numbers as digits or words)."""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import jiwer

from amiro.core.config import ConfigError
from amiro.dialogue.asr import Recognizer, Transcript, gate
from amiro.dialogue.audio import read_wav
from amiro.dialogue.schema import OUT_OF_SCOPE
from amiro.dialogue.spoken_numbers import wer_normalize
from amiro.dialogue.text import normalize

ROC_THRESHOLDS = (0.0, 0.3, 0.4, 0.5, 0.6, 0.7)


@dataclass(frozen=True)
class Heard:
    """One recording, its reference and what the recogniser made of it (before rejection)."""

    file: str
    reference: str
    transcript: Transcript
    seconds: float
    decode_s: float


def reference(wav: Path, lang: str = "en") -> str:
    sidecar = wav.with_suffix(".txt")
    text = sidecar.read_text(encoding="utf-8") if sidecar.is_file() else wav.stem.replace("_", " ")
    return wer_normalize(text, lang)


def transcribe_dir(directory: Path, recognizer: Recognizer, lang: str = "en") -> list[Heard]:
    if not directory.is_dir():
        raise ConfigError(f"{directory}: no such directory")
    wavs = sorted(directory.glob("*.wav"))
    if not wavs:
        raise ConfigError(f"{directory}: no .wav files")
    heard = []
    for wav in wavs:
        audio = read_wav(wav)
        start = time.perf_counter()
        transcript = recognizer.transcribe(audio)
        decode_s = time.perf_counter() - start
        heard.append(Heard(wav.name, reference(wav, lang), transcript, audio.seconds, decode_s))
    return heard


def accuracy_report(
    heard: list[Heard], reject_below: float = 0.0, lang: str = "en"
) -> dict[str, Any]:
    """The contract's ``files``, ``wer``, ``sentence_accuracy``, ``rtf`` on what is left after
    rejecting results below ``reject_below`` (a rejected command counts as not recognised)."""
    kept = [gate(h.transcript, reject_below) for h in heard]
    hyps = [wer_normalize(t.text, lang) for t in kept]
    refs = [h.reference for h in heard]
    audio_s = sum(h.seconds for h in heard)
    rows = [
        {
            "file": h.file,
            "reference": h.reference,
            "hypothesis": wer_normalize(h.transcript.guess, lang),
            "confidence": round(h.transcript.confidence, 4),
            "accepted": not t.rejected,
        }
        for h, t in zip(heard, kept, strict=True)
    ]
    return {
        "files": len(heard),
        "wer": jiwer.wer(refs, [h or "<empty>" for h in hyps]),
        "sentence_accuracy": sum(r == h for r, h in zip(refs, hyps, strict=True)) / len(heard),
        "rtf": sum(h.decode_s for h in heard) / audio_s if audio_s else 0.0,
        "reject_below": reject_below,
        "rejected": sum(bool(t.rejected) for t in kept) / len(heard),
        "results": rows,
    }


def evaluate_asr(
    directory: Path, recognizer: Recognizer, reject_below: float = 0.0, lang: str = "en"
) -> dict[str, Any]:
    return accuracy_report(transcribe_dir(directory, recognizer, lang), reject_below, lang)


def _rates(
    in_grammar: list[Heard],
    out_of_grammar: list[Heard],
    threshold: float,
    intent_of: Callable[[str], str],
) -> dict[str, float]:
    accepted = [t.text for t in (gate(h.transcript, threshold) for h in out_of_grammar) if t.text]
    kept = [gate(h.transcript, threshold) for h in in_grammar]
    pairs = zip(in_grammar, kept, strict=True)
    correct = sum(wer_normalize(t.text) == h.reference for h, t in pairs)
    return {
        "threshold": threshold,
        "false_acceptance_rate": len(accepted) / len(out_of_grammar),
        "false_action_rate": sum(intent_of(a) != OUT_OF_SCOPE for a in accepted)
        / len(out_of_grammar),
        "false_rejection_rate": sum(bool(t.rejected) for t in kept) / len(in_grammar),
        "sentence_accuracy": correct / len(in_grammar),
    }


def rejection_report(
    in_grammar: list[Heard],
    out_of_grammar: list[Heard],
    reject_below: float,
    intent_of: Callable[[str], str],
    thresholds: Iterable[float] = ROC_THRESHOLDS,
) -> dict[str, Any]:
    """False acceptance (out-of-grammar speech or noise given a transcript), false action (a
    transcript that the NLU reads as a command, not ``out_of_scope``) and false rejection
    (in-grammar speech rejected), at ``reject_below`` and at a few other thresholds."""
    at = _rates(in_grammar, out_of_grammar, reject_below, intent_of)
    return {
        "out_of_grammar_files": len(out_of_grammar),
        "false_acceptance_rate": at["false_acceptance_rate"],
        "false_action_rate": at["false_action_rate"],
        "false_rejection_rate": at["false_rejection_rate"],
        "roc": [_rates(in_grammar, out_of_grammar, t, intent_of) for t in thresholds],
        "out_of_grammar_results": [
            {
                "file": h.file,
                "hypothesis": normalize(h.transcript.guess),
                "confidence": round(h.transcript.confidence, 4),
                "accepted": bool(text),
                "intent": intent_of(text) if text else OUT_OF_SCOPE,
            }
            for h, text in ((h, gate(h.transcript, reject_below).text) for h in out_of_grammar)
        ],
    }


def describe_rates(rates: dict[str, float]) -> str:
    """One line of the ROC table, for people."""
    pct = {k: f"{100 * v:.1f}%" for k, v in rates.items()}
    return (
        f"threshold {rates['threshold']:.2f}: false acceptance {pct['false_acceptance_rate']} "
        f"(acted on {pct['false_action_rate']}), false rejection "
        f"{pct['false_rejection_rate']}, sentence accuracy {pct['sentence_accuracy']}"
    )
