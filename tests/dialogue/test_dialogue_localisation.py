"""Every answer in Romanian and French is wholly in that language: no English room, device,
state or place name, and no phrase falling back to its English text."""

from __future__ import annotations

import itertools
from importlib import resources
from typing import Any

import pytest
import yaml

from amiro.dialogue.actions import Actions
from amiro.dialogue.phrases import phrase
from amiro.dialogue.sources import offline_sources
from amiro.dialogue.text import tokens
from amiro.dialogue.training_data import shipped_training_data

ROOMS = ("kitchen", "bedroom", "living_room", "bathroom", "hallway")
STATES = {"lights": ("on", "off", "open", "close"), "blinds": ("open", "close", "on", "off")}
DAYS = ("today", "tomorrow", "yesterday", "2026-07-20", "2026-12-03")
# Every city the NLU can hear, in any language (and none: the home's).
HEARD = {
    name.lower()
    for lang in ("en", "ro", "fr")
    for name in shipped_training_data(lang).lookups["location_entity"]
}
PLACES = ("", "bucharest", "bucurești", "bucarest", "london", "londra", *sorted(HEARD))
CALENDAR_TITLES = {"physiotherapy", "visit", "from", "doctor", "s", "appointment"}  # user data


def _table() -> dict[str, dict[str, str]]:
    text = resources.files("amiro").joinpath("data/dialogue/phrases.yaml").read_text("utf-8")
    table: dict[str, dict[str, str]] = yaml.safe_load(text)
    return table


def _english_only() -> set[str]:
    """Words of the English phrases that no Romanian or French phrase uses."""
    table = _table()
    english = {w for entry in table.values() for w in tokens(entry["en"])}
    other = {w for entry in table.values() for lang in ("ro", "fr") for w in tokens(entry[lang])}
    return english - other - {"pepper"}


def _answers(lang: str) -> list[str]:
    """Every answer the actions can give, over every slot value."""
    actions = Actions(offline_sources(), submit=lambda kind, payload: None)
    runs: list[tuple[str, dict[str, str]]] = []
    for device, states in STATES.items():
        runs += [
            ("control_device", {"device_entity": device, "device_state": s, "room_entity": r})
            for s, r in itertools.product(states, ROOMS)
        ]
    runs += [("go_to", {"room_entity": r}) for r in ROOMS] + [("go_to", {"person_entity": "ion"})]
    for day, place in itertools.product(DAYS, PLACES):
        runs.append(("answer_weather", {"dateandtime_entity": day, "location_entity": place}))
        runs.append(("answer_calendar", {"dateandtime_entity": day}))
        for metric in ("blood_pressure", "heart_rate", "steps", "sleep", "health_status"):
            runs.append(("answer_health", {"dateandtime_entity": day, "health_entity": metric}))
    runs += [("answer_info", {"info_entity": v}) for v in ("identity", "name", "capabilities")]
    runs += [("answer_postpone", {"duration": d}) for d in ("PT2H", "P3D", "")]
    out = []
    for action, slots in runs:
        key, fields = actions.run(action, slots, "maria", lang)
        out.append(phrase(key, lang, fields))
    return out


def test_every_phrase_has_romanian_and_french() -> None:
    missing = [k for k, entry in _table().items() for lang in ("ro", "fr") if not entry.get(lang)]
    assert missing == []


@pytest.mark.parametrize("lang", ["ro", "fr"])
def test_no_english_word_in_any_answer(lang: str) -> None:
    english = _english_only() - CALENDAR_TITLES
    assert {"kitchen", "lights", "bucharest", "living", "done"} <= english
    table: dict[str, Any] = _table()
    said = _answers(lang) + [entry[lang] for entry in table.values()]
    leaks = {text: sorted(set(tokens(text)) & english) for text in said}
    assert {t: w for t, w in leaks.items() if w} == {}


@pytest.mark.parametrize(
    ("lang", "place", "said"),
    [
        ("fr", "bucharest", "à Bucarest"),
        ("fr", "london", "à Londres"),
        ("ro", "bucharest", "în București"),
        ("ro", "", "în București"),  # the home's, named in English in the sources
        ("ro", "marseille", "în Marsilia"),
        ("en", "bucurești", "in Bucharest"),
    ],
)
def test_cities_are_said_by_their_local_name(lang: str, place: str, said: str) -> None:
    actions = Actions(offline_sources())
    slots = {"dateandtime_entity": "today", "location_entity": place}
    key, fields = actions.run("answer_weather", slots, "maria", lang)
    assert said in phrase(key, lang, fields)


@pytest.mark.parametrize(
    ("lang", "said"),
    [("en", "On 20 July 2026"), ("fr", "Le 20 juillet 2026"), ("ro", "Pe 20 iulie 2026")],
)
def test_a_date_is_said_the_languages_way(lang: str, said: str) -> None:
    key, fields = Actions(offline_sources()).run(
        "answer_calendar", {"dateandtime_entity": "2026-07-20"}, "maria", lang
    )
    assert phrase(key, lang, fields).startswith(said)
