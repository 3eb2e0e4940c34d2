"""Transcripts compared the way people read them: case, punctuation and diacritics dropped
(:func:`amiro.dialogue.text.normalize`) and numbers written as digits spelt out, so that
"3 hours" and "three hours" (or "trois heures", "trei ore") are the same words for the word
error rate.  Whole numbers 0-999 in en, fr and ro; larger ones keep their digits."""

from __future__ import annotations

import re

from amiro.dialogue.text import normalize

_UNITS = {
    "en": "zero one two three four five six seven eight nine ten eleven twelve thirteen "
    "fourteen fifteen sixteen seventeen eighteen nineteen",
    "fr": "zero un deux trois quatre cinq six sept huit neuf dix onze douze treize quatorze "
    "quinze seize dix-sept dix-huit dix-neuf",
    "ro": "zero unu doi trei patru cinci sase sapte opt noua zece unsprezece doisprezece "
    "treisprezece paisprezece cincisprezece saisprezece saptesprezece optsprezece "
    "nouasprezece",
}
_TENS = {
    "en": "_ _ twenty thirty forty fifty sixty seventy eighty ninety",
    "fr": "_ _ vingt trente quarante cinquante soixante soixante quatre-vingt quatre-vingt",
    "ro": "_ _ douazeci treizeci patruzeci cincizeci saizeci saptezeci optzeci nouazeci",
}
_HUNDRED = {"en": "hundred", "fr": "cent", "ro": "sute"}
_DIGITS = re.compile(r"\d+")


def _below_100(n: int, lang: str) -> str:
    units, tens = _UNITS[lang].split(), _TENS[lang].split()
    if n < 20:
        return units[n]
    ten, unit = divmod(n, 10)
    if lang == "fr" and ten in (7, 9):  # soixante-dix, quatre-vingt-onze
        return f"{tens[ten]} {units[10 + unit]}"
    if unit == 0:
        return tens[ten]
    if lang == "ro":
        return f"{tens[ten]} si {units[unit]}"
    if lang == "fr" and unit == 1 and ten < 8:
        return f"{tens[ten]} et un"
    return f"{tens[ten]} {units[unit]}"


def spell(n: int, lang: str) -> str:
    """``n`` (0-999) in words, normalised; other numbers as digits."""
    if not 0 <= n < 1000:
        return str(n)
    hundreds, rest = divmod(n, 100)
    if hundreds == 0:
        return _below_100(n, lang)
    if lang == "ro":
        head = "o suta" if hundreds == 1 else f"{_below_100(hundreds, lang)} sute"
    elif lang == "fr":
        head = "cent" if hundreds == 1 else f"{_below_100(hundreds, lang)} cent"
    else:
        head = f"{_below_100(hundreds, lang)} {_HUNDRED[lang]}"
    return head if rest == 0 else f"{head} {_below_100(rest, lang)}"


def wer_normalize(text: str, lang: str = "en") -> str:
    """Lower case, no punctuation or diacritics, numbers in words (hyphens as spaces)."""
    spelt = _DIGITS.sub(lambda m: f" {spell(int(m.group()), lang)} ", text)
    return normalize(spelt)
