"""The NLU's confusion matrix per language, for ``amiro nlu evaluate``: as a labelled text
table (rows: the true intent, columns: the predicted one) and as a plot, a panel per
language with each row normalised to the share of that intent's utterances."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from amiro.evaluation.confusion_plot import Panel, plot_panels

Confusion = dict[str, dict[str, int]]


def short(intent: str) -> str:
    """A column heading: ``get_weather`` → ``weather``, ``out_of_scope`` → ``oos``."""
    if intent == "out_of_scope":
        return "oos"
    return intent.removeprefix("get_").removeprefix("control_")


def labels(confusion: Confusion) -> list[str]:
    """Every intent seen as true or predicted, out_of_scope last."""
    found = set(confusion) | {p for row in confusion.values() for p in row}
    return sorted(found, key=lambda n: (n == "out_of_scope", n))


def matrix(confusion: Confusion) -> tuple[list[str], np.ndarray]:
    names = labels(confusion)
    counts = np.array([[confusion.get(t, {}).get(p, 0) for p in names] for t in names])
    return names, counts


def table(confusion: Confusion) -> str:
    """Rows are the true intents, columns the predicted ones; zeros shown as dots."""
    names, counts = matrix(confusion)
    heads = [short(n) for n in names]
    width = max(len(n) for n in names)
    cols = [max(len(h), len(str(counts[:, j].max()))) for j, h in enumerate(heads)]
    lines = [" " * width + " | " + " ".join(h.rjust(c) for h, c in zip(heads, cols, strict=True))]
    for name, row in zip(names, counts, strict=True):
        cells = [(str(v) if v else ".").rjust(c) for v, c in zip(row, cols, strict=True)]
        lines.append(name.rjust(width) + " | " + " ".join(cells))
    return "\n".join(["true \\ predicted", *lines])


def plot(report: dict[str, Any], path: Path, title: str) -> None:
    """A panel per language: row-normalised shares, the counts written in the cells."""
    panels = []
    for lang, r in report.items():
        names, counts = matrix(r["confusion"])
        scope = "" if r["in_scope_accuracy"] is None else f", in scope {r['in_scope_accuracy']:.1%}"
        oos = r["out_of_scope_rejection"]
        refused = "" if oos is None else f", oos refused {oos:.1%}"
        panels.append(Panel(f"{lang} (n={r['n']}{scope}{refused})", names, counts))
    plot_panels(panels, path, title, short)
