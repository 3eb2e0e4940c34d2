"""Text normalisation shared by training and parsing, so that typos in diacritics, case and
punctuation (and ASR output, which has none) all look the same to the models."""

from __future__ import annotations

import re
import unicodedata

_LIGATURES = str.maketrans({"œ": "oe", "æ": "ae", "ß": "ss", "’": "'", "`": "'"})
_NON_WORD = re.compile(r"[^0-9a-z]+")


def normalize(text: str) -> str:
    """Lower case, no diacritics, words separated by single spaces (``"Arată-mi"`` →
    ``"arata mi"``); ISO dates keep their digits (``"2024-06-12"`` → ``"2024 06 12"``)."""
    decomposed = unicodedata.normalize("NFKD", text.lower().translate(_LIGATURES))
    plain = "".join(c for c in decomposed if not unicodedata.combining(c))
    return _NON_WORD.sub(" ", plain).strip()


def tokens(text: str) -> list[str]:
    return normalize(text).split()
