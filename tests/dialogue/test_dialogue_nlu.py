"""The NLU: the simulator's replies, the held-out files, robustness and the CLI."""

from __future__ import annotations

import json
from importlib import resources
from pathlib import Path

import pytest

from amiro.commands.dialogue import register
from amiro.core.config import ConfigError
from amiro.core.messages import SpeechHeard
from amiro.dialogue.nlu_eval import evaluate, read_jsonl
from amiro.dialogue.training_data import parse_training_data
from amiro.dialogue.understanding import Nlu
from amiro.sim.phrases import INTENTS, PHRASES

EVAL_DIR = Path(str(resources.files("amiro").joinpath("data/dialogue/eval")))


@pytest.fixture(scope="module")
def nlu() -> Nlu:
    return Nlu()


def test_every_resident_reply_is_understood(nlu: Nlu) -> None:
    for lang, contexts in PHRASES.items():
        for replies in contexts.values():
            for kind, variants in replies.items():
                for text in variants:
                    heard = SpeechHeard(text, lang, speaker="maria")
                    assert nlu.intent(heard)[0] == INTENTS[kind], (lang, text)


@pytest.mark.parametrize("lang", ["en", "ro", "fr"])
def test_held_out_accuracy(nlu: Nlu, lang: str) -> None:
    report = evaluate(read_jsonl(EVAL_DIR / f"{lang}.jsonl"), lambda lg, t: nlu.parse(t, lg))
    assert report[lang]["n"] >= 60
    assert report[lang]["intent_accuracy"] >= 0.93
    assert report[lang]["entity_accuracy"] >= 0.9
    assert sum(sum(row.values()) for row in report[lang]["confusion"].values()) == report[lang]["n"]


@pytest.mark.parametrize(
    ("lang", "text", "intent", "entities"),
    [
        (
            "ro",
            "afiseaza tensiunea de ieri",
            "get_health",
            {
                "health_entity": "blood_pressure",
                "output_entity": "display",
                "dateandtime_entity": "yesterday",
            },
        ),
        (
            "fr",
            "eteins la lumiere du salon",
            "control_device",
            {"device_entity": "lights", "device_state": "off", "room_entity": "living_room"},
        ),
        (
            "en",
            "whats the wether in pariss tomorow",
            "get_weather",
            {"location_entity": "paris", "dateandtime_entity": "tomorrow"},
        ),
        ("en", "remind me in 15 minutes", "postpone", {"duration": "PT15M"}),
        (
            "en",
            "what plans do I have on 2024-07-01",
            "get_calendar",
            {"dateandtime_entity": "2024-07-01"},
        ),
    ],
)
def test_typos_and_missing_diacritics(
    nlu: Nlu, lang: str, text: str, intent: str, entities: dict[str, str]
) -> None:
    parsed = nlu.parse(text, lang)
    assert parsed.intent == intent
    assert {k: parsed.entities.get(k) for k in entities} == entities


def test_entities_only_those_the_intent_carries(nlu: Nlu) -> None:
    parsed = nlu.parse("yes, turn on the lights", "en")
    assert parsed.intent != "affirm" or parsed.entities == {}


def test_gibberish_is_out_of_scope(nlu: Nlu) -> None:
    assert nlu.parse("", "en").intent == "out_of_scope"
    assert nlu.parse("zzqx vlorp", "fr").intent == "out_of_scope"


def test_bad_training_data_is_a_config_error() -> None:
    with pytest.raises(ConfigError, match="nlu"):
        parse_training_data({"language": "en"}, "x.yaml")
    with pytest.raises(ConfigError, match="without intent"):
        parse_training_data({"nlu": [{"examples": "- hi"}]}, "x.yaml")


def test_bad_eval_file_is_a_config_error(tmp_path: Path) -> None:
    bad = tmp_path / "bad.jsonl"
    bad.write_text('{"lang": "en", "text": "hi"}\n', encoding="utf-8")
    with pytest.raises(ConfigError, match=r"bad\.jsonl:1"):
        read_jsonl(bad)
    with pytest.raises(ConfigError, match="no such file"):
        read_jsonl(tmp_path / "missing.jsonl")


def _run(argv: list[str]) -> int:
    import argparse

    parser = argparse.ArgumentParser()
    register(parser.add_subparsers())
    args = parser.parse_args(argv)
    code: int = args.handler(args)
    return code


def test_cli_parse_and_evaluate_json(capsys: pytest.CaptureFixture[str]) -> None:
    assert _run(["nlu", "parse", "--lang", "fr", "quelle", "est", "ma", "tension", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["intent"]["name"] == "get_health"
    assert out["entities"] == {"health_entity": "blood_pressure"}
    assert _run(["nlu", "evaluate", str(EVAL_DIR / "ro.jsonl"), "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert set(report["ro"]) >= {
        "n",
        "intent_accuracy",
        "entity_accuracy",
        "confusion",
        "ms_per_utterance",
    }


def test_cli_unknown_language() -> None:
    with pytest.raises(ConfigError, match="unknown language"):
        _run(["nlu", "parse", "--lang", "de", "hallo"])
