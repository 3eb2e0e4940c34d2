"""``amiro nlu bench``: the cost of understanding, measured on this machine: training the
three languages' NLU from scratch (amiro's data plus MASSIVE train when found), and one
dialogue turn (NLU plus dialogue manager) over amiro's held-out utterances.  Wall time is
read only here, to measure speed."""

from __future__ import annotations

import statistics
from typing import Any

from amiro.core.clock import wall_seconds
from amiro.dialogue.actions import Actions
from amiro.dialogue.domain import shipped_domain
from amiro.dialogue.manager import DialogueManager
from amiro.dialogue.nlu import LanguageNlu
from amiro.dialogue.nlu_eval import read_jsonl, shipped_eval_files
from amiro.dialogue.sources import offline_sources
from amiro.dialogue.training_data import shipped_training_data
from amiro.dialogue.understanding import Nlu, real_examples

LANGS = ("en", "ro", "fr")


def training_s() -> dict[str, float]:
    """Seconds to read the data and train each language (reading MASSIVE included)."""
    real_examples.cache_clear()
    out = {}
    for lang in LANGS:
        started = wall_seconds()
        LanguageNlu(shipped_training_data(lang), real=real_examples(lang))
        out[lang] = wall_seconds() - started
    return out


def turn_ms(repeats: int) -> dict[str, dict[str, float]]:
    """Median and 95th percentile ms per turn, every held-out utterance ``repeats`` times."""
    nlu = Nlu()
    manager = DialogueManager(nlu, shipped_domain(), Actions(offline_sources(), lambda k, p: 0))
    out = {}
    for path, lang in zip(shipped_eval_files(), LANGS, strict=True):
        nlu.model(lang)  # trained outside the timing
        times = []
        for _ in range(repeats):
            for row in read_jsonl(path):
                started = wall_seconds()
                manager.handle(row.text, lang, "bench")
                times.append(1000.0 * (wall_seconds() - started))
        times.sort()
        out[lang] = {
            "median": statistics.median(times),
            "p95": times[int(0.95 * (len(times) - 1))],
        }
    return out


def bench(repeats: int = 3) -> dict[str, Any]:
    train = training_s()
    return {
        "massive": bool(real_examples("en")),
        "training_s": {**train, "total": sum(train.values())},
        "turn_ms": turn_ms(repeats),
    }
