"""Entity extraction: fuzzy gazetteer matching over word n-grams, plus ISO dates, relative
days and durations in digits or words (:mod:`amiro.dialogue.when`).  Fuzzy matching
(rapidfuzz) absorbs typos, missing diacritics and ASR slips such as "tension" for
"tensiunea"; the intent then keeps only the keys it can carry."""

from __future__ import annotations

import re
from dataclasses import dataclass

from rapidfuzz import fuzz, process

from amiro.dialogue.text import normalize
from amiro.dialogue.when import time_entities

_ISO_DATE = re.compile(r"\b(\d{4}) (\d{2}) (\d{2})\b")
PHRASE_KEYS = ("info_entity",)


@dataclass(frozen=True)
class Entity:
    key: str
    value: str
    start: int  # first token
    end: int  # one past the last token
    score: float


def min_score(surface: str) -> float:
    """Short words must match exactly (``"on"`` vs ``"no"``); longer ones tolerate typos."""
    if len(surface) <= 4:
        return 100.0
    return 80.0


class EntityExtractor:
    def __init__(self, gazetteer: dict[str, set[tuple[str, str]]], lang: str) -> None:
        self.gazetteer = gazetteer
        self.lang = lang  # the language of the time expressions
        self.surfaces = list(gazetteer)
        self.max_len = max((len(s.split()) for s in self.surfaces), default=1)

    def _match(self, candidate: str) -> tuple[str, float] | None:
        if candidate in self.gazetteer:
            return candidate, 100.0
        if len(candidate) <= 4:
            return None
        found = process.extractOne(
            candidate, self.surfaces, scorer=fuzz.ratio, score_cutoff=min_score(candidate)
        )
        return None if found is None else (found[0], float(found[1]))

    def extract(self, text: str, allowed: tuple[str, ...] | None = None) -> list[Entity]:
        """Non-overlapping entities, longest and best matches first."""
        words = normalize(text).split()
        found: list[Entity] = []
        for n in range(min(self.max_len, len(words)), 0, -1):
            for i in range(len(words) - n + 1):
                match = self._match(" ".join(words[i : i + n]))
                if match is None:
                    continue
                surface, score = match
                for key, value in sorted(self.gazetteer[surface]):
                    if allowed is None or key in allowed:
                        found.append(Entity(key, value, i, i + n, score))
        found += [e for e in _patterns(words, self.lang) if allowed is None or e.key in allowed]
        found = _resolve(found)
        missing = [k for k in PHRASE_KEYS if (allowed is None or k in allowed)]
        missing = [k for k in missing if all(e.key != k for e in found)]
        return found + [e for k in missing if (e := self._whole(" ".join(words), k))]

    def _whole(self, text: str, key: str) -> Entity | None:
        """An entity whose surface forms are whole questions ("who are you"), matched on the
        bag of words so that inserted words ("who exactly are you") still match."""
        choices = [s for s, pairs in self.gazetteer.items() if any(k == key for k, _ in pairs)]
        found = process.extractOne(text, choices, scorer=fuzz.token_set_ratio, score_cutoff=75)
        if found is None:
            return None
        value = next(v for k, v in sorted(self.gazetteer[found[0]]) if k == key)
        return Entity(key, value, 0, 0, float(found[1]))


def _patterns(words: list[str], lang: str) -> list[Entity]:
    """ISO dates, then relative days and durations: they win over the gazetteer's words."""
    out: list[Entity] = []
    if m := _ISO_DATE.search(" ".join(words)):
        out.append(Entity("dateandtime_entity", "-".join(m.groups()), 0, 0, 100.0))
    out += [Entity(key, value, 0, 0, 100.0) for key, value in time_entities(words, lang)]
    return out


def _resolve(found: list[Entity]) -> list[Entity]:
    """One value per key and no two entities on the same words: pattern matches win, then
    exact matches (longest first), then fuzzy ones (best first)."""
    found.sort(
        key=lambda e: (e.end == e.start, e.score == 100.0, e.end - e.start, e.score), reverse=True
    )
    taken: set[int] = set()
    keys: set[str] = set()
    out: list[Entity] = []
    for e in found:
        span = set(range(e.start, e.end))
        if e.key in keys or span & taken:
            continue
        keys.add(e.key)
        taken |= span
        out.append(e)
    return out
