"""The speech grammar generated from the NLU data, its hints, and the audio helpers the
speech test sets are made with (no recognition here: see test_dialogue_speech)."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from amiro.core.config import ConfigError
from amiro.dialogue.asr_testset import SHIPPED_COMMANDS, file_name, read_commands
from amiro.dialogue.audio import Audio, add_noise_at_snr, add_noise_floor
from amiro.dialogue.grammar import GrammarHints, jsgf, load_hints, shipped_hints, spoken_words
from amiro.dialogue.training_data import parse_training_data

DATA = parse_training_data(
    {
        "nlu": [
            {"intent": "get_weather", "examples": "- what's the weather for [today](when)\n"},
            {"intent": "affirm", "examples": "- yes\n- of course\n"},
            {"intent": "deny", "examples": "- no\n- xyzzy never\n"},
            {"synonym": "today", "examples": "- today\n- tonight\n"},
        ]
    },
    "test",
)
HINTS = GrammarHints(lead=("please",), tail=("now",), before={"when": ("for", "on")})


def accepts(grammar: str, sentence: str) -> bool:
    """Whether the (flat, as generated) JSGF accepts ``sentence``: expanded into a regex."""
    rules = dict(re.findall(r"^(?:public )?<(\w+)> = (.*);$", grammar, re.M))

    def expand(body: str) -> str:
        # every word matches itself and the space after it
        body = re.sub(r"(?<![<\w'])([a-z']+)(?![\w'>])", "\\1\0", body).replace(" ", "")
        body = re.sub(r"<(\w+)>", lambda m: f"(?:{expand(rules[m.group(1)])})", body)
        return body.replace("\0", " ").replace("[", "(?:").replace("]", ")?")

    return re.fullmatch(expand(rules["utterance"]), sentence + " ") is not None


def test_spoken_words_keep_apostrophes() -> None:
    words = spoken_words("What's up, Ștefan? I'm 'here'")
    assert words == ["what's", "up", "stefan", "i'm", "here"]


def test_grammar_generalises_with_hints_and_entities() -> None:
    grammar = jsgf(DATA, lambda w: w != "xyzzy", hints=HINTS)
    for sentence in ("what's the weather for today", "please what's the weather on tonight now"):
        assert accepts(grammar, sentence), sentence
    assert accepts(grammar, "what's the weather tonight")  # the preposition is optional
    assert not accepts(grammar, "what s the weather for today")  # "s" would be the letter
    assert not accepts(grammar, "xyzzy never")  # a word the dictionary lacks: left out
    assert not accepts(grammar, "yes no")


def test_answers_chain_two_alike_answers_without_lead() -> None:
    grammar = jsgf(DATA, lambda w: True, ("affirm", "deny"), HINTS, chain=True)
    assert accepts(grammar, "yes of course") and accepts(grammar, "no now")
    assert not accepts(grammar, "please yes") and not accepts(grammar, "yes no")
    assert not accepts(grammar, "what's the weather for today")


def test_pronunciations_make_words_speakable() -> None:
    hints = GrammarHints(pronunciations={"xyzzy": "Z IH Z IY"})
    assert accepts(jsgf(DATA, lambda w: w != "xyzzy", hints=hints), "xyzzy never")


def test_shipped_hints_and_commands() -> None:
    hints = shipped_hints("en")
    assert "please" in hints.tail and "on" in hints.before["dateandtime_entity"]
    assert hints.pronunciations["iasi"]
    commands = read_commands(SHIPPED_COMMANDS)
    assert len(commands) >= 30 and len(set(commands)) == len(commands)
    assert file_name("what's your name robot") == "what's_your_name_robot.wav"


def test_bad_hints_and_commands(tmp_path: Path) -> None:
    bad = tmp_path / "hints.yaml"
    bad.write_text("lead: please\n", encoding="utf-8")
    with pytest.raises(ConfigError, match="'lead' must be a list of strings"):
        load_hints(bad)
    bad.write_text("before: [1, 2\n", encoding="utf-8")
    with pytest.raises(ConfigError, match="invalid YAML"):
        load_hints(bad)
    with pytest.raises(ConfigError, match="no such file"):
        load_hints(tmp_path / "missing.yaml")
    (tmp_path / "empty.txt").write_text("# nothing\n\n", encoding="utf-8")
    with pytest.raises(ConfigError, match="no commands"):
        read_commands(tmp_path / "empty.txt")


def test_noise_at_snr_and_floor_are_seeded() -> None:
    tone = Audio((3000 * np.sin(np.arange(16000) / 5.0)).astype(np.int16), 16000)
    noisy = add_noise_at_snr(tone, np.random.default_rng(3), 10.0)
    noise = noisy.samples.astype(float) - tone.samples
    snr = 10 * np.log10(np.mean(tone.samples.astype(float) ** 2) / np.mean(noise**2))
    assert abs(snr - 10.0) < 0.2
    again = add_noise_at_snr(tone, np.random.default_rng(3), 10.0)
    assert np.array_equal(noisy.samples, again.samples)
    silence = Audio(np.zeros(16000, np.int16), 16000)
    floor = add_noise_floor(silence, np.random.default_rng(0)).samples
    assert 5.0 < floor.std() < 15.0
