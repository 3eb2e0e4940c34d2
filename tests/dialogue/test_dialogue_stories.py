"""Story-driven dialogue: follow-ups continue the story of the last turn with its slots
carried, in every language; a follow-up no story explains gets the fallback."""

from __future__ import annotations

from pathlib import Path

import pytest

from amiro.core.config import ConfigError
from amiro.dialogue.actions import Actions
from amiro.dialogue.domain import load_dm, load_domain, shipped_domain
from amiro.dialogue.manager import DialogueManager
from amiro.dialogue.phrases import phrase
from amiro.dialogue.sources import RecordingDevices, offline_sources
from amiro.dialogue.stories import load_stories, shipped_dm_dir
from amiro.dialogue.understanding import Nlu

H, D, L, INFO = "health_entity", "dateandtime_entity", "location_entity", "info_entity"
# (what the user says, the action, the slots expected after the turn)
CONVERSATIONS = {
    "en": [
        ("how is my blood pressure", "answer_health", {H: "blood_pressure"}),
        ("and yesterday?", "answer_health", {H: "blood_pressure", D: "yesterday"}),
        ("and my heart rate?", "answer_health", {H: "heart_rate", D: "yesterday"}),
        ("what will the weather be like tomorrow", "answer_weather", {D: "tomorrow"}),
        ("and in Paris?", "answer_weather", {D: "tomorrow", L: "paris"}),
        ("what do I have today", "answer_calendar", {D: "today"}),
        ("and tomorrow?", "answer_calendar", {D: "tomorrow"}),
        ("who are you", "answer_info", {INFO: "identity"}),
        ("and what can you do?", "answer_info", {INFO: "capabilities"}),
    ],
    "fr": [
        ("quelle est ma tension", "answer_health", {H: "blood_pressure"}),
        ("et hier ?", "answer_health", {H: "blood_pressure", D: "yesterday"}),
        ("quel temps fait-il aujourd'hui", "answer_weather", {D: "today"}),
        ("et demain ?", "answer_weather", {D: "tomorrow"}),
        ("et à Londres ?", "answer_weather", {D: "tomorrow", L: "londres"}),
        ("qu'est-ce que j'ai aujourd'hui", "answer_calendar", {D: "today"}),
        ("et demain ?", "answer_calendar", {D: "tomorrow"}),
        ("qui es-tu", "answer_info", {INFO: "identity"}),
        ("et que sais-tu faire ?", "answer_info", {INFO: "capabilities"}),
    ],
    "ro": [
        ("cum este tensiunea mea", "answer_health", {H: "blood_pressure"}),
        ("și ieri?", "answer_health", {H: "blood_pressure", D: "yesterday"}),
        ("cum e vremea azi", "answer_weather", {D: "today"}),
        ("și mâine?", "answer_weather", {D: "tomorrow"}),
        ("și la Londra?", "answer_weather", {D: "tomorrow", L: "londra"}),
        ("ce am în calendar azi", "answer_calendar", {D: "today"}),
        ("și mâine?", "answer_calendar", {D: "tomorrow"}),
        ("cine ești", "answer_info", {INFO: "identity"}),
        ("și ce știi să faci?", "answer_info", {INFO: "capabilities"}),
    ],
}  # fmt: skip

FOLLOWUP = {"en": "and yesterday?", "fr": "et hier ?", "ro": "și ieri?"}
# A device, then the same in another room, then another state: (said, room, device, state).
DEVICES = {
    "en": [
        ("turn on the kitchen lights", "kitchen", "lights", "on"),
        ("and in the bedroom?", "bedroom", "lights", "on"),
        ("and now off", "bedroom", "lights", "off"),
    ],
    "fr": [
        ("allume la lumière de la cuisine", "kitchen", "lights", "on"),
        ("et dans la chambre ?", "bedroom", "lights", "on"),
        ("et maintenant éteins", "bedroom", "lights", "off"),
    ],
    "ro": [
        ("aprinde lumina în bucătărie", "kitchen", "lights", "on"),
        ("și în dormitor?", "bedroom", "lights", "on"),
        ("și acum stinge", "bedroom", "lights", "off"),
    ],
}


def manager() -> DialogueManager:
    return DialogueManager(Nlu(), shipped_domain(), Actions(offline_sources()))


@pytest.mark.parametrize("lang", sorted(CONVERSATIONS))
def test_follow_ups_continue_the_story_with_carried_slots(lang: str) -> None:
    dm = manager()
    for text, action, slots in CONVERSATIONS[lang]:
        answer = dm.handle(text, lang, "maria")
        assert answer.action == action, (text, answer)
        assert slots.items() <= answer.entities.items(), (text, answer.entities)
    texts = [t.answer.text for t in dm.history]
    assert texts[0] != texts[1]  # yesterday's reading, not today's said again


@pytest.mark.parametrize("lang", sorted(DEVICES))
def test_a_device_follow_up_carries_the_device_to_another_room(lang: str) -> None:
    sources = offline_sources()
    dm = DialogueManager(Nlu(), shipped_domain(), Actions(sources))
    assert isinstance(sources.devices, RecordingDevices)
    for text, room, device, state in DEVICES[lang]:
        answer = dm.handle(text, lang, "maria")
        assert answer.action == "control_device", (text, answer)
        assert sources.devices.states[(room, device)] == state, text
    assert sources.devices.states[("kitchen", "lights")] == "on"


def test_a_users_own_stories_and_rules_drive_the_dialogue(tmp_path: Path) -> None:
    """A folder with some of the files: its own replace amiro's, the others are amiro's."""
    (tmp_path / "stories.en.yml").write_text('followup: {en: ["then", "and"]}\n')
    rules = (shipped_dm_dir() / "rules.yml").read_text(encoding="utf-8")
    (tmp_path / "rules.yml").write_text(
        rules.replace(
            "{intent: greet}, {action: utter_greet}", "{intent: greet}, {action: answer_info}"
        )
    )
    domain, stories = load_dm(tmp_path)
    dm = DialogueManager(Nlu(), domain, Actions(offline_sources()), stories=stories)
    assert dm.handle("hello", "en", "maria").action == "answer_info"
    dm.handle("what will the weather be like tomorrow", "en", "maria")
    answer = dm.handle("then in Paris?", "en", "maria")
    assert answer.action == "answer_weather"
    assert answer.entities[L] == "paris"
    assert stories.followup["fr"] == load_dm(None)[1].followup["fr"]  # amiro's French file


def test_a_users_domain_brings_its_own_responses_per_language(tmp_path: Path) -> None:
    domain = (shipped_dm_dir() / "domain.yml").read_text(encoding="utf-8")
    (tmp_path / "domain.yml").write_text(
        domain + 'responses:\n  utter_welcome: {en: "Welcome home!", ro: "Bine ați venit!"}\n'
    )
    rules = (shipped_dm_dir() / "rules.yml").read_text(encoding="utf-8")
    (tmp_path / "rules.yml").write_text(
        rules.replace("action: utter_greet}", "action: utter_welcome}")
    )
    domain_, stories = load_dm(tmp_path)
    dm = DialogueManager(Nlu(), domain_, Actions(offline_sources()), stories=stories)
    assert dm.handle("bună ziua", "ro", "maria").text == "Bine ați venit!"
    assert dm.handle("bonjour", "fr", "maria").text == "Welcome home!"  # no French: English
    assert dm.handle("au revoir", "fr", "maria").text == phrase("utter_goodbye", "fr")


def test_a_rule_naming_a_response_nobody_wrote_is_a_one_line_error(tmp_path: Path) -> None:
    rules = (shipped_dm_dir() / "rules.yml").read_text(encoding="utf-8")
    (tmp_path / "rules.yml").write_text(rules.replace("action: utter_greet}", "action: utter_hi}"))
    with pytest.raises(ConfigError, match="no response named utter_hi"):
        load_dm(tmp_path)


def test_a_language_file_holds_only_its_own_follow_up_words(tmp_path: Path) -> None:
    path = tmp_path / "stories.fr.yml"
    path.write_text('followup: {en: ["and"]}\n')
    with pytest.raises(ConfigError, match="only 'fr' words"):
        load_dm(tmp_path)
    with pytest.raises(ConfigError, match="no such directory"):
        load_dm(tmp_path / "missing")


@pytest.mark.parametrize("lang", sorted(FOLLOWUP))
def test_a_follow_up_with_no_story_gets_the_fallback(lang: str) -> None:
    answer = manager().handle(FOLLOWUP[lang], lang, "maria")
    assert answer.action == "utter_fallback"
    assert answer.text == phrase("utter_fallback", lang)


def test_follow_ups_are_per_user() -> None:
    dm = manager()
    dm.handle("how is my blood pressure", "en", "maria")
    assert dm.handle("and yesterday?", "en", "ion").action == "utter_fallback"
    assert dm.handle("and yesterday?", "en", "maria").action == "answer_health"


def test_a_misspelt_story_file_is_a_one_line_error_naming_it(tmp_path: Path) -> None:
    path = tmp_path / "stories.yml"
    path.write_text(
        "followup: {en: [and]}\nstories:\n  - story: x\n    steps:\n      - intnet: greet\n"
    )
    with pytest.raises(ConfigError) as err:
        load_stories(path)
    assert str(path) in str(err.value) and "intnet" in str(err.value)
    assert "\n" not in str(err.value)


def test_a_misspelt_rules_file_is_a_one_line_error_naming_it(tmp_path: Path) -> None:
    domain, rules = tmp_path / "domain.yaml", tmp_path / "rules.yml"
    domain.write_text("actions: {}\n")
    rules.write_text(
        "rules:\n  - rule: greet\n    steps: [{intent: greet}, {acton: utter_greet}]\n"
    )
    with pytest.raises(ConfigError) as err:
        load_domain(domain, rules)
    assert str(rules) in str(err.value) and "acton" in str(err.value)
    assert "\n" not in str(err.value)


def test_the_shipped_rules_answer_each_intent_with_its_slots() -> None:
    rule = shipped_domain().rule("get_health")
    assert rule is not None and rule.action == "answer_health"
    assert rule.required == ("health_entity",)
    assert rule.defaults == {"dateandtime_entity": "today"}
