"""Relative dates and durations as people say them, in English, French and Romanian: "the day
after tomorrow", "in three days", "il y a deux jours", "lundi", "peste două ore", "une heure
et demie", digits or words.  Durations are ISO 8601 (``PT2H``, ``PT1H30M``, ``P3D``).  Days
one away keep CONTRACTS.md's words (today, tomorrow, yesterday); the others stay relative
(``today+3``, ``weekday:0``) until :func:`resolve_day` dates them on the runtime clock, so
that "in three days" means three days after the simulated home's today, not the host's."""

from __future__ import annotations

import re
from collections.abc import Sequence
from datetime import date, timedelta

from amiro.dialogue.numbers import read_number

UNIT_WORDS: dict[str, dict[str, str]] = {
    "en": {"minute": "M", "minutes": "M", "min": "M", "mins": "M", "hour": "H", "hours": "H"}
    | {"day": "D", "days": "D", "week": "W", "weeks": "W"},
    "fr": {"minute": "M", "minutes": "M", "min": "M", "heure": "H", "heures": "H", "h": "H"}
    | {"jour": "D", "jours": "D", "semaine": "W", "semaines": "W"},
    "ro": {"minut": "M", "minute": "M", "minutul": "M", "ora": "H", "ore": "H", "orei": "H"}
    | {"zi": "D", "zile": "D", "saptamana": "W", "saptamani": "W"},
}
MINUTES = {"M": 1, "H": 60}
DAYS = {"D": 1, "W": 7}
BETWEEN = {"en": ("of",), "fr": ("d",), "ro": ("de",)}  # "douăzeci de minute"
# After an hour: "an hour and a half", "une heure et demie", "o oră și jumătate".
HALF = {"en": ("and a half",), "fr": ("et demie", "et demi"), "ro": ("si jumatate",)}
# Durations said without a number (normalised words -> minutes).
FIXED: dict[str, dict[str, int]] = {
    "en": {"half an hour": 30, "half hour": 30, "quarter of an hour": 15, "quarter hour": 15},
    "fr": {"demi heure": 30, "quart d heure": 15, "trois quarts d heure": 45},
    "ro": {"jumatate de ora": 30, "jumatate ora": 30, "sfert de ora": 15},
}
# Words before (or after) a number of days that say which way it counts.
FUTURE_BEFORE = {"en": ("in",), "fr": ("dans", "d ici"), "ro": ("peste", "in")}
PAST_BEFORE = {"en": (), "fr": ("il y a",), "ro": ("acum", "in urma cu")}
FUTURE_AFTER = {"en": ("from now", "later"), "fr": ("plus tard",), "ro": ("mai tarziu",)}
PAST_AFTER = {"en": ("ago", "before"), "fr": ("avant", "plus tot"), "ro": ("in urma",)}
DAY_WORDS: dict[str, dict[str, int]] = {
    "en": {"day after tomorrow": 2, "day before yesterday": -2},
    "fr": {"apres demain": 2, "avant hier": -2},
    "ro": {"poimaine": 2, "poimine": 2, "alaltaieri": -2, "alaltaseara": -2},
}
WEEKDAYS: dict[str, tuple[str, ...]] = {
    "en": ("monday", "tuesday", "wednesday", "thursday", "friday", "saturday", "sunday"),
    "fr": ("lundi", "mardi", "mercredi", "jeudi", "vendredi", "samedi", "dimanche"),
    "ro": ("luni", "marti", "miercuri", "joi", "vineri", "sambata", "duminica"),
}
NEAR_DAYS = {-1: "yesterday", 0: "today", 1: "tomorrow"}
_RELATIVE = re.compile(r"^today([+-]\d+)$")
_WEEKDAY = re.compile(r"^weekday:([0-6])$")
_ISO_DURATION = re.compile(r"^P(?:(\d+)D)?(?:T(?:(\d+)H)?(?:(\d+)M)?)?$")


def _at(words: Sequence[str], i: int, phrase: str) -> bool:
    said = phrase.split()
    return list(words[i : i + len(said)]) == said


def _before(words: Sequence[str], i: int, phrases: Sequence[str]) -> bool:
    return any(_at(words, i - len(p.split()), p) for p in phrases if i >= len(p.split()))


def _after_number(words: Sequence[str], i: int, lang: str) -> bool:
    """Whether ``words[i]`` follows a number ("five" in "twenty five"; "luni", months, in
    "două luni")."""
    return i > 0 and read_number(words, i - 1, lang) is not None


def day_value(offset: int) -> str:
    return NEAR_DAYS.get(offset, f"today{offset:+d}")


def duration_value(minutes: int = 0, days: int = 0) -> str:
    hours, rest = divmod(minutes, 60)
    clock = (f"{hours}H" if hours else "") + (f"{rest}M" if rest else "")
    return ("P" + (f"{days}D" if days else "") + (f"T{clock}" if clock else "")) or "PT0M"


def _amount(words: Sequence[str], i: int, lang: str) -> tuple[int, str, int] | None:
    """A number, then a unit (``"două ore"``, ``"20 de minute"``): (amount, unit, end)."""
    number = read_number(words, i, lang)
    if number is None:
        return None
    value, j = number
    if j < len(words) and words[j] in BETWEEN[lang]:
        j += 1
    unit = UNIT_WORDS[lang].get(words[j]) if j < len(words) else None
    return None if unit is None else (value, unit, j + 1)


def time_entities(words: Sequence[str], lang: str) -> list[tuple[str, str]]:
    """``(key, value)`` for the first duration (``duration``) and day
    (``dateandtime_entity``) said in the normalised ``words`` (none in other languages)."""
    found: dict[str, str] = {}
    if lang not in UNIT_WORDS:
        return []
    for i in range(len(words)):
        for phrase, minutes in FIXED[lang].items():
            if _at(words, i, phrase):
                found.setdefault("duration", duration_value(minutes))
        for phrase, offset in DAY_WORDS[lang].items():
            if _at(words, i, phrase):
                found.setdefault("dateandtime_entity", day_value(offset))
        if words[i] in WEEKDAYS[lang] and not _after_number(words, i, lang):
            found.setdefault("dateandtime_entity", f"weekday:{WEEKDAYS[lang].index(words[i])}")
        amount = None if _after_number(words, i, lang) else _amount(words, i, lang)
        if amount is None:
            continue
        value, unit, end = amount
        if unit in MINUTES:
            extra = 30 if unit == "H" and any(_at(words, end, h) for h in HALF[lang]) else 0
            found.setdefault("duration", duration_value(value * MINUTES[unit] + extra))
            continue
        days = value * DAYS[unit]
        if _before(words, i, PAST_BEFORE[lang]) or any(
            _at(words, end, p) for p in PAST_AFTER[lang]
        ):
            found.setdefault("dateandtime_entity", day_value(-days))
        elif _before(words, i, FUTURE_BEFORE[lang]) or any(
            _at(words, end, p) for p in FUTURE_AFTER[lang]
        ):
            found.setdefault("dateandtime_entity", day_value(days))
            found.setdefault("duration", duration_value(days=days))
    return list(found.items())


def resolve_day(value: str, today: date) -> str:
    """A day value with ``today`` known: relative ones as ISO dates (the next such weekday,
    today included), those one day away or less as today, tomorrow or yesterday."""
    if m := _RELATIVE.match(value):
        offset = int(m.group(1))
    elif m := _WEEKDAY.match(value):
        offset = (int(m.group(1)) - today.weekday()) % 7
    else:
        return value
    return NEAR_DAYS.get(offset) or (today + timedelta(days=offset)).isoformat()


def duration_seconds(value: str) -> float | None:
    """Seconds of an ISO 8601 duration in days, hours and minutes; None when it is not one."""
    m = _ISO_DURATION.match(value)
    if m is None or not any(m.groups()):
        return None
    days, hours, minutes = (int(g or 0) for g in m.groups())
    return 60.0 * (minutes + 60 * (hours + 24 * days))
