"""A confidence for pocketsphinx grammar-mode results, which pocketsphinx does not give (its
posterior is always 1 in grammar mode, so any speech comes out as some grammar sentence).

The recogniser decodes the same audio twice: with the grammar and with a free phone loop
(any phone after any phone), the usual reference for what the audio sounds like.  Speech the
grammar cannot explain shows in two ways, each measured on espeak-ng sentences outside the
grammar (docs/dialogue.md):

- *unexplained*: the grammar path hides it in silence: the share of the frames the phone
  loop hears as speech that the grammar path spends outside its words;
- *gap*: the grammar forces its words onto it: per frame of those words, how far their
  acoustic score falls below the phone loop's on the same frames (pocketsphinx log units,
  base 1.0001).  Noise alone is caught here.

Each measure is scaled so that its limit reads 0.5; the confidence is the worse of the two.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

# Tuned on the first 30 out-of-grammar sentences and the 38 in-grammar commands, clean
# (data/dialogue/grammar/asr_en_oog.txt, asr_en.txt): no correct command lost, clean or at
# 20 dB SNR; every out-of-grammar one rejected clean.
UNEXPLAINED_LIMIT = 0.08
GAP_LIMIT = 33.0
SILENT_PHONES = ("SIL",)  # and the filler phones, "+NSN+" etc.


@dataclass(frozen=True)
class Segment:
    """A word (grammar) or phone (phone loop) of a decoded path."""

    label: str
    start: int  # first frame
    end: int  # last frame, inclusive
    ascore: int  # acoustic score, log units


@dataclass(frozen=True)
class GrammarFit:
    unexplained: float
    gap: float

    def confidence(self) -> float:
        worst = min(
            1.0 - self.unexplained / (2.0 * UNEXPLAINED_LIMIT), 1.0 - self.gap / (2.0 * GAP_LIMIT)
        )
        return float(np.clip(worst, 0.0, 1.0))


def is_grammar_word(label: str) -> bool:
    """Not a filler: ``<sil>``, ``<s>``, ``[NOISE]``, or the ``(NULL)`` of empty transitions."""
    return not label.startswith(("<", "[", "+", "("))


def is_speech_phone(label: str) -> bool:
    return label not in SILENT_PHONES and not label.startswith("+")


def _frames(
    segments: Iterable[Segment], n_frames: int, keep: Callable[[str], bool]
) -> tuple[npt.NDArray[np.bool_], npt.NDArray[np.float64]]:
    """Which frames the kept segments cover, and every segment's score spread over its frames."""
    covered = np.zeros(n_frames, dtype=bool)
    score = np.zeros(n_frames)
    for seg in segments:
        if seg.start < 0 or seg.end < seg.start:  # empty transitions take no frame
            continue
        score[seg.start : seg.end + 1] = seg.ascore / (seg.end - seg.start + 1)
        covered[seg.start : seg.end + 1] = keep(seg.label)
    return covered, score


def grammar_fit(grammar: Iterable[Segment], phones: Iterable[Segment], n_frames: int) -> GrammarFit:
    words, grammar_score = _frames(grammar, n_frames, is_grammar_word)
    speech, phone_score = _frames(phones, n_frames, is_speech_phone)
    if not words.any():
        return GrammarFit(1.0, float("inf"))
    unexplained = float((speech & ~words).sum()) / max(int(speech.sum()), 1)
    gap = float((phone_score - grammar_score)[words].mean())
    return GrammarFit(unexplained, gap)
