"""Numbers as people say them, in digits or words, in English, French and Romanian ("2",
"twenty five", "vingt et un", "dix-sept", "douăzeci și cinci"), read from normalised tokens
(no diacritics, hyphens split), for the durations and day offsets of :mod:`when`."""

from __future__ import annotations

from collections.abc import Sequence

# "a"/"an"/"o"/"un"/"une" count as one only where a unit follows ("an hour", "o oră"):
# :func:`read_number` is only asked there.
UNITS: dict[str, dict[str, int]] = {
    "en": {
        "zero": 0, "a": 1, "an": 1, "one": 1, "two": 2, "three": 3, "four": 4, "five": 5,
        "six": 6, "seven": 7, "eight": 8, "nine": 9, "ten": 10, "eleven": 11, "twelve": 12,
        "thirteen": 13, "fourteen": 14, "fifteen": 15, "sixteen": 16, "seventeen": 17,
        "eighteen": 18, "nineteen": 19, "couple": 2,
    },
    "fr": {
        "zero": 0, "un": 1, "une": 1, "deux": 2, "trois": 3, "quatre": 4, "cinq": 5,
        "six": 6, "sept": 7, "huit": 8, "neuf": 9, "dix": 10, "onze": 11, "douze": 12,
        "treize": 13, "quatorze": 14, "quinze": 15, "seize": 16,
    },
    "ro": {
        "zero": 0, "o": 1, "un": 1, "unu": 1, "una": 1, "doi": 2, "doua": 2, "trei": 3,
        "patru": 4, "cinci": 5, "sase": 6, "sapte": 7, "opt": 8, "noua": 9, "zece": 10,
        "unsprezece": 11, "unspe": 11, "doisprezece": 12, "douasprezece": 12, "doispe": 12,
        "treisprezece": 13, "paisprezece": 14, "cincisprezece": 15, "saisprezece": 16,
        "saptesprezece": 17, "optsprezece": 18, "nouasprezece": 19,
    },
}  # fmt: skip
TENS: dict[str, dict[str, int]] = {
    "en": {"twenty": 20, "thirty": 30, "forty": 40, "fifty": 50, "sixty": 60, "ninety": 90},
    "fr": {"vingt": 20, "trente": 30, "quarante": 40, "cinquante": 50, "soixante": 60},
    "ro": {"douazeci": 20, "treizeci": 30, "patruzeci": 40, "cincizeci": 50, "saizeci": 60},
}
AND = {"en": "and", "fr": "et", "ro": "si"}  # "vingt et un", "douăzeci și unu"
FR_TEENS = {"sept": 17, "huit": 18, "neuf": 19}  # "dix-sept"


def read_number(words: Sequence[str], i: int, lang: str) -> tuple[int, int] | None:
    """The number starting at ``words[i]`` and the index just past it, or None."""
    if i >= len(words):
        return None
    word = words[i]
    if word.isdigit():
        return int(word), i + 1
    if word in TENS[lang]:
        value, j = TENS[lang][word], i + 1
        if j < len(words) and words[j] == AND[lang]:
            j += 1
        unit = UNITS[lang].get(words[j]) if j < len(words) else None
        if unit is not None and 1 <= unit <= 9 and words[j] not in ("a", "an", "o"):
            return value + unit, j + 1
        return value, i + 1
    if lang == "fr" and word == "dix" and i + 1 < len(words) and words[i + 1] in FR_TEENS:
        return FR_TEENS[words[i + 1]], i + 2
    if word in UNITS[lang]:
        return UNITS[lang][word], i + 1
    return None
