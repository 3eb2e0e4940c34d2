"""``amiro nlu choose-margin``: how ``nlu.OUT_OF_SCOPE_MARGIN`` was chosen, reproducible.
Each language's model is trained once; for every candidate margin the MASSIVE dev partition
(validation data, mapped) is parsed, and the margin with the best mean of in-scope accuracy
and out-of-scope rejection over the languages wins.  Never run it on test data."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from amiro.core.config import ConfigError
from amiro.dialogue.massive import ENV_DIR, massive_partition, read_massive
from amiro.dialogue.nlu import LanguageNlu
from amiro.dialogue.nlu_eval import Labelled, evaluate
from amiro.dialogue.schema import OUT_OF_SCOPE
from amiro.dialogue.understanding import shipped_model

LANGS = ("en", "ro", "fr")
CANDIDATES = tuple(round(0.1 * i, 1) for i in range(9))


def _scores(
    model: LanguageNlu, rows: list[Labelled], progress: Callable[[str, int, int], None] | None
) -> dict[str, float]:
    r = evaluate(rows, lambda _lang, text: model.parse(text), progress)[model.lang]
    return {k: r[k] for k in ("in_scope_accuracy", "out_of_scope_rejection")}


def sweep(
    candidates: Sequence[float] = CANDIDATES,
    progress: Callable[[str, int, int], None] | None = None,
) -> dict[str, Any]:
    """Per margin and language: in-scope accuracy and out-of-scope rejection on dev."""
    table: dict[float, dict[str, dict[str, float]]] = {m: {} for m in candidates}
    for lang in LANGS:
        path = massive_partition(lang, "dev")
        if path is None:
            raise ConfigError(f"MASSIVE dev not found: set {ENV_DIR}")
        rows = read_massive(path)
        model = shipped_model(lang)
        kept = model.offsets
        try:
            for margin in candidates:
                model.offsets = np.where(np.array(model.labels) == OUT_OF_SCOPE, margin, 0.0)
                table[margin][lang] = _scores(model, rows, progress)
        finally:
            model.offsets = kept

    def score(margin: float) -> float:
        per_lang = table[margin].values()
        return float(
            np.mean([(v["in_scope_accuracy"] + v["out_of_scope_rejection"]) / 2 for v in per_lang])
        )

    best = max(candidates, key=score)
    return {
        "best": best,
        "margins": [{"margin": m, "score": score(m), **table[m]} for m in candidates],
    }
