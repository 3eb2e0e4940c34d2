"""Residents: scripted replies in their language, hearing range, activities."""

from __future__ import annotations

import numpy as np
import pytest

from amiro.core.messages import SpeechHeard, SpeechRequest
from amiro.core.runtime import Runtime
from amiro.dialogue.output import speaking_time
from amiro.sim.config import SimConfig
from amiro.sim.phrases import PHRASES
from amiro.sim.residents import Resident, ScriptedReply
from amiro.sim.simulator import build_sim


def test_script_is_followed_in_order_then_repeats() -> None:
    r = Resident(
        "ana",
        0.0,
        0.0,
        language="ro",
        script={
            "hydration_reminder": [ScriptedReply("postpone", 1.0), ScriptedReply("confirm", 2.0)],
            "default": [ScriptedReply("deny")],
        },
    )
    g = np.random.default_rng(0)
    first = r.reply_to("hydration_reminder", g)
    second = r.reply_to("hydration_reminder", g)
    third = r.reply_to("hydration_reminder", g)
    assert first is not None and second is not None and third is not None
    assert (first.intent, second.intent, third.intent) == ("postpone", "affirm", "affirm")
    assert first.delay == 1.0 and second.delay == 2.0
    assert first.lang == "ro" and first.text in PHRASES["ro"]["hydration"]["postpone"]
    assert second.text in PHRASES["ro"]["hydration"]["confirm"]
    other = r.reply_to("activity_confirmation", g)  # falls back to the default script
    assert other is not None and other.intent == "deny"
    assert other.text in PHRASES["ro"]["generic"]["deny"]


def test_silence_and_default_confirm() -> None:
    g = np.random.default_rng(0)
    quiet = Resident("q", 0, 0, script={"default": [ScriptedReply("silence")]})
    assert quiet.reply_to("hydration_reminder", g) is None
    easy = Resident("e", 0, 0, language="fr")
    reply = easy.reply_to("hydration_reminder", g)
    assert reply is not None and reply.intent == "affirm"
    assert reply.text in PHRASES["fr"]["hydration"]["confirm"]


def test_wording_is_seeded() -> None:
    def texts(seed: int) -> list[str]:
        g = np.random.default_rng(seed)
        r = Resident("x", 0, 0)
        return [r.reply_to("hydration_reminder", g).text for _ in range(12)]  # type: ignore[union-attr]

    assert texts(1) == texts(1)
    assert texts(1) != texts(2)
    assert len(set(texts(1))) > 1  # variants are used


def test_bad_resident() -> None:
    with pytest.raises(ValueError):
        Resident("x", 0, 0, language="de")
    with pytest.raises(ValueError):
        Resident("x", 0, 0, activity="juggling")


def sim_config() -> SimConfig:
    return SimConfig.model_validate(
        {
            "start": "couch",
            "residents": [
                {
                    "name": "maria",
                    "language": "ro",
                    "at": "couch_left",
                    "posture": "sitting_couch",
                    "script": {
                        "hydration_reminder": [
                            {"reply": "postpone", "delay": 1.5},
                            {"reply": "confirm", "delay": 2.0},
                        ]
                    },
                },
                {
                    "name": "john",
                    "language": "en",
                    "at": "kitchen_chair",
                    "posture": "sitting_desk",
                },
            ],
        }
    )


def run_dialogue(seed: int) -> tuple[list[tuple[float, SpeechHeard]], object]:
    rt = Runtime(seed=seed)
    sim = build_sim(rt, sim_config())
    heard: list[tuple[float, SpeechHeard]] = []

    rt.bus.subscribe(
        "/amiro/speech/heard", SpeechHeard, lambda m: heard.append((rt.clock.now(), m))
    )
    say = rt.bus.publisher("/amiro/say", SpeechRequest)
    rt.start()
    rt.spin_for(1.0)
    say.publish(SpeechRequest("Maria, ai băut apă?", "ro", act="hydration_reminder"))
    rt.spin_for(5.0)
    say.publish(SpeechRequest("Maria, ai băut apă?", "ro", act="hydration_reminder"))
    rt.spin_for(5.0)
    return heard, sim


def test_replies_on_the_bus_follow_script_language_and_timing() -> None:
    heard, sim = run_dialogue(3)
    assert [m.intent for _, m in heard] == ["postpone", "affirm"]
    assert all(m.speaker == "maria" and m.lang == "ro" for _, m in heard)
    speaking = speaking_time("Maria, ai băut apă?")  # people answer after the robot spoke
    assert heard[0][0] == pytest.approx(1.0 + speaking + 1.5, abs=0.01)
    assert heard[1][0] == pytest.approx(6.0 + speaking + 2.0, abs=0.01)
    maria = sim.residents.residents["maria"]  # type: ignore[attr-defined]
    assert maria.activity == "drink_water"  # confirmed a hydration reminder
    rt = sim.robot.runtime  # type: ignore[attr-defined]
    rt.spin_for(8.5)  # the 8 s of drinking end
    assert maria.activity == "idle"
    again, _ = run_dialogue(3)
    assert [m.text for _, m in again] == [m.text for _, m in heard]


def test_only_residents_near_the_robot_answer() -> None:
    rt = Runtime(seed=0)
    sim = build_sim(rt, sim_config())
    heard: list[SpeechHeard] = []
    rt.bus.subscribe("/amiro/speech/heard", SpeechHeard, heard.append)
    rt.start()
    # john is in the kitchen, far away; addressing him explicitly gets no answer
    rt.bus.publish("/amiro/say", SpeechRequest("John?", addressee="john"))
    rt.spin_for(4.0)
    assert heard == []
    # maria is near (2 m) and answers an unaddressed prompt
    rt.bus.publish("/amiro/say", SpeechRequest("Hello?"))
    rt.spin_for(4.0)
    assert [m.speaker for m in heard] == ["maria"]
    sim.residents.set_present("maria", False)
    rt.bus.publish("/amiro/say", SpeechRequest("Hello?"))
    rt.spin_for(4.0)
    assert len(heard) == 1
