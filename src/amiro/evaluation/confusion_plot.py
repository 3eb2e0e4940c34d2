"""Confusion matrices drawn side by side, one panel each (NLU per language, activity per
protocol): rows normalised to the share of each true class, the counts written in the cells."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np


@dataclass(frozen=True)
class Panel:
    title: str
    labels: Sequence[str]  # rows (true) and columns (predicted), in the same order
    counts: np.ndarray


def plot_panels(
    panels: Sequence[Panel], path: Path, title: str, short: Callable[[str], str] = str
) -> None:
    """Write one figure with a panel per matrix; ``short`` turns a label into a tick."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    size = max(len(p.labels) for p in panels)
    fig, axes = plt.subplots(
        1, len(panels), figsize=(0.55 * size * len(panels) + 2, 0.55 * size + 2.4)
    )
    for ax, panel in zip(np.atleast_1d(axes), panels, strict=True):
        counts = panel.counts
        shares = counts / np.maximum(counts.sum(axis=1, keepdims=True), 1)
        ax.imshow(shares, cmap="Blues", vmin=0.0, vmax=1.0)
        for (i, j), n in np.ndenumerate(counts):
            if n:
                colour = "white" if shares[i, j] > 0.6 else "black"
                ax.text(j, i, str(n), ha="center", va="center", fontsize=7, color=colour)
        heads = [short(n) for n in panel.labels]
        ax.set_xticks(range(len(heads)), heads, rotation=60, ha="right", fontsize=8)
        ax.set_yticks(range(len(heads)), heads, fontsize=8)
        ax.set_xlabel("predicted")
        ax.set_ylabel("true")
        ax.set_title(panel.title, fontsize=9)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
