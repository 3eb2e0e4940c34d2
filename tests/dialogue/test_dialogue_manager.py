"""Dialogue management on the shipped domain, rules and stories: slot filling, outputs and
the go_to callback."""

from __future__ import annotations

from typing import Any

import pytest

from amiro.dialogue.actions import Actions
from amiro.dialogue.domain import shipped_domain
from amiro.dialogue.manager import DialogueManager
from amiro.dialogue.sources import RecordingDevices, offline_sources
from amiro.dialogue.understanding import Nlu

# Conversations the dialogue manager must hold: each step is what the user says and the
# action (or question) the robot answers with.
STORIES: list[dict[str, Any]] = [
    {
        "story": "blood pressure on the screen only",
        "lang": "en",
        "steps": [
            {"user": "display my blood pressure", "action": "answer_health"}
            | {"display": True, "say": False}
        ],
    },
    {
        "story": "the paper's default output is display and say",
        "lang": "en",
        "steps": [
            {"user": "what is my blood pressure", "action": "answer_health"}
            | {"display": True, "say": True}
        ],
    },
    {
        "story": "lights, asking for the room",
        "lang": "en",
        "steps": [
            {"user": "turn on the lights", "ask": "room_entity"},
            {"user": "in the kitchen", "action": "control_device"},
        ],
    },
    {
        "story": "health, asking which measurement",
        "lang": "ro",
        "steps": [
            {"user": "arată-mi datele", "ask": "health_entity"},
            {"user": "pulsul", "action": "answer_health"},
        ],
    },
    {
        "story": "cancelling a question",
        "lang": "fr",
        "steps": [
            {"user": "ferme les volets", "ask": "room_entity"},
            {"user": "non laisse tomber", "action": "utter_cancelled"},
        ],
    },
    {
        "story": "weather and goodbye",
        "lang": "fr",
        "steps": [
            {"user": "quel temps fera-t-il demain", "action": "answer_weather"},
            {"user": "au revoir", "action": "utter_goodbye"},
        ],
    },
    {"story": "go to maria", "lang": "en", "steps": [{"user": "go to maria", "action": "go_to"}]},
]


def manager(submitted: list[tuple[str, dict[str, Any]]] | None = None) -> DialogueManager:
    sink = submitted if submitted is not None else []
    actions = Actions(offline_sources(), lambda kind, payload: sink.append((kind, payload)))
    return DialogueManager(Nlu(), shipped_domain(), actions)


@pytest.mark.parametrize("story", STORIES, ids=[s["story"] for s in STORIES])
def test_story(story: dict[str, Any]) -> None:
    dm = manager()
    for step in story["steps"]:
        answer = dm.handle(step["user"], story["lang"], "maria")
        assert answer.lang == story["lang"]
        if "ask" in step:
            assert answer.ask == step["ask"], step
        else:
            assert answer.action == step["action"], (step, answer)
        for flag in ("display", "say"):
            if flag in step:
                assert getattr(answer, flag) is step[flag]


def test_go_to_submits_a_behaviour() -> None:
    submitted: list[tuple[str, dict[str, Any]]] = []
    answer = manager(submitted).handle("du-te la Maria", "ro", "ion")
    assert submitted == [("go_to", {"person_entity": "maria", "requested_by": "ion", "lang": "ro"})]
    assert answer.text == "Merg la Maria."


def test_device_is_actuated_after_the_room_is_given() -> None:
    sources = offline_sources()
    dm = DialogueManager(Nlu(), shipped_domain(), Actions(sources))
    assert dm.handle("allume la lumière", "fr", "u").ask == "room_entity"
    assert dm.awaiting("u")
    dm.handle("dans la cuisine", "fr", "u")
    assert isinstance(sources.devices, RecordingDevices)
    assert sources.devices.states == {("kitchen", "lights"): "on"}
    assert not dm.awaiting("u")


def test_answers_come_from_the_sources_in_the_users_language() -> None:
    dm = manager()
    assert "126/79" in dm.handle("afișează tensiunea", "ro", "maria").text
    assert (
        dm.handle("combien de pas ai-je fait hier", "fr", "maria").text
        == "Hier, vous avez fait 5167 pas."
    )
    assert len(dm.history) == 2


def test_go_to_without_engine_says_so() -> None:
    dm = DialogueManager(Nlu(), shipped_domain(), Actions(offline_sources()))
    assert dm.handle("go to the kitchen", "en").text == "I cannot move right now."
