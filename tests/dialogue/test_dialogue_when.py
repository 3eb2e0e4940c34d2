"""Numbers, relative days and durations in en, fr and ro, in digits and words, dated on the
runtime's (simulated) clock rather than the host's."""

from __future__ import annotations

from datetime import date

import pytest

from amiro.core.clock import SimClock
from amiro.dialogue.actions import Actions
from amiro.dialogue.domain import shipped_domain
from amiro.dialogue.manager import DialogueManager
from amiro.dialogue.numbers import read_number
from amiro.dialogue.sources import offline_sources
from amiro.dialogue.text import tokens
from amiro.dialogue.understanding import Nlu
from amiro.dialogue.when import duration_seconds, resolve_day, time_entities

DAY = 86400.0
# Three days after the simulated epoch (2026-07-15, a Wednesday): Saturday 2026-07-18, 10:00.
START = 3 * DAY
D, T = "dateandtime_entity", "duration"

CASES = [
    ("en", "remind me in two hours", "postpone", {T: "PT2H"}),
    ("en", "ask me again in 45 minutes", "postpone", {T: "PT45M"}),
    ("en", "try again in twenty five minutes", "postpone", {T: "PT25M"}),
    ("en", "come back in an hour and a half", "postpone", {T: "PT1H30M"}),
    ("en", "what will the weather be like the day after tomorrow", "get_weather",
     {D: "2026-07-20"}),
    ("en", "what do I have in three days", "get_calendar", {D: "2026-07-21"}),
    ("en", "what was my blood pressure two days ago", "get_health", {D: "2026-07-16"}),
    ("en", "what's on my calendar on monday", "get_calendar", {D: "2026-07-20"}),
    ("en", "what do I have tomorrow", "get_calendar", {D: "tomorrow"}),
    ("fr", "rappelle-moi dans deux heures", "postpone", {T: "PT2H"}),
    ("fr", "redemande-moi dans un quart d'heure", "postpone", {T: "PT15M"}),
    ("fr", "dans une heure et demie", "postpone", {T: "PT1H30M"}),
    ("fr", "rappelle-moi dans vingt et une minutes", "postpone", {T: "PT21M"}),
    ("fr", "quel temps fera-t-il après-demain", "get_weather", {D: "2026-07-20"}),
    ("fr", "qu'est-ce que j'ai dans trois jours", "get_calendar", {D: "2026-07-21"}),
    ("fr", "quelle était ma tension il y a deux jours", "get_health", {D: "2026-07-16"}),
    ("fr", "quel temps fera-t-il dimanche", "get_weather", {D: "tomorrow"}),
    ("fr", "quel temps fera-t-il demain", "get_weather", {D: "tomorrow"}),
    ("ro", "amintește-mi peste două ore", "postpone", {T: "PT2H"}),
    ("ro", "reamintește-mi peste o oră și jumătate", "postpone", {T: "PT1H30M"}),
    ("ro", "peste douăzeci și cinci de minute", "postpone", {T: "PT25M"}),
    ("ro", "cum va fi vremea poimâine", "get_weather", {D: "2026-07-20"}),
    ("ro", "ce am în calendar peste trei zile", "get_calendar", {D: "2026-07-21"}),
    ("ro", "care era tensiunea mea acum două zile", "get_health", {D: "2026-07-16"}),
    ("ro", "ce am de făcut luni", "get_calendar", {D: "2026-07-20"}),
    ("ro", "cum va fi vremea mâine", "get_weather", {D: "tomorrow"}),
]  # fmt: skip


@pytest.fixture(scope="module")
def nlu() -> Nlu:
    return Nlu(clock=SimClock(start=START))


@pytest.mark.parametrize(("lang", "text", "intent", "entities"), CASES)
def test_days_and_durations_are_read_and_dated_on_the_clock(
    nlu: Nlu, lang: str, text: str, intent: str, entities: dict[str, str]
) -> None:
    parsed = nlu.parse(text, lang)
    assert parsed.intent == intent
    assert entities.items() <= parsed.entities.items(), parsed.entities


def test_the_same_words_mean_another_date_on_another_day() -> None:
    later = Nlu(clock=SimClock(start=START + 10 * DAY))
    assert later.parse("what do I have in three days", "en").entities[D] == "2026-07-31"


@pytest.mark.parametrize(
    ("lang", "said", "value"),
    [
        ("en", "forty two", 42),
        ("en", "seventeen", 17),
        ("en", "12", 12),
        ("fr", "dix-sept", 17),
        ("fr", "cinquante et un", 51),
        ("fr", "trente-cinq", 35),
        ("ro", "douăzeci și trei", 23),
        ("ro", "paisprezece", 14),
        ("ro", "două", 2),
    ],
)
def test_numbers_in_words_and_digits(lang: str, said: str, value: int) -> None:
    words = tokens(said)
    assert read_number(words, 0, lang) == (value, len(words))


def test_a_number_of_months_is_not_a_weekday() -> None:
    """Romanian "luni" is Monday and also "months"."""
    assert time_entities(tokens("peste două luni"), "ro") == []
    assert time_entities(tokens("luni"), "ro") == [(D, "weekday:0")]


def test_days_resolve_against_today() -> None:
    saturday = date(2026, 7, 18)
    assert resolve_day("today+2", saturday) == "2026-07-20"
    assert resolve_day("today-1", saturday) == "yesterday"
    assert resolve_day("weekday:5", saturday) == "today"  # the next Saturday is today
    assert resolve_day("weekday:0", saturday) == "2026-07-20"
    assert resolve_day("2024-06-12", saturday) == "2024-06-12"
    assert duration_seconds("PT1H30M") == 5400.0
    assert duration_seconds("P3D") == 3 * DAY
    assert duration_seconds("later") is None


@pytest.mark.parametrize(
    ("lang", "text", "said"),
    [
        ("en", "ask me again in two hours", "All right, I will ask you again at 12:00."),
        ("fr", "rappelle-moi dans une demi-heure", "D'accord, je vous le redemanderai à 10:30."),
        ("ro", "reamintește-mi peste trei zile", "Bine, vă întreb din nou la 2026-07-21 10:00."),
        ("en", "not now", "All right."),
    ],
)
def test_postponing_says_when_on_the_clock(lang: str, text: str, said: str) -> None:
    clock = SimClock(start=START)
    actions = Actions(offline_sources(), clock=clock)
    dm = DialogueManager(Nlu(clock=clock), shipped_domain(), actions)
    assert dm.handle(text, lang, "maria").text == said
