"""``amiro chat``: a banner saying how to quit, then only the robot's replies (``--debug``
adds what was understood), all in the chosen language, with the user's own DM folder."""

from __future__ import annotations

import io
from pathlib import Path

import pytest

from amiro.cli import main

SAID = "bonjour\nallume la lumière de la cuisine\net dans la chambre ?\nau revoir\nencore\n"


def _chat(
    argv: list[str], said: str, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> tuple[int, list[str], list[str], str]:
    """Exit code, the replies, the other lines of stdout (prompts aside), stderr."""
    monkeypatch.setattr("sys.stdin", io.StringIO(said))
    code = main(["chat", *argv])
    out = capsys.readouterr()
    lines = [line.replace("you> ", "") for line in out.out.splitlines()]
    replies = [line.removeprefix("robot> ") for line in lines if line.startswith("robot> ")]
    other = [line for line in lines if line.strip() and not line.startswith("robot> ")]
    return code, replies, other, out.err


def test_chat_shows_only_the_replies_and_stops_at_goodbye(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    code, replies, other, err = _chat(["--lang", "fr"], SAID, monkeypatch, capsys)
    assert code == 0
    assert "Ctrl-D" in err and "(français)" in err and "dites « au revoir »" in err  # in French
    assert other == []  # no intent, no entities
    assert replies == [
        "Bonjour ! Comment puis-je vous aider ?",
        "C'est fait : lumières allumées dans la cuisine.",
        "C'est fait : lumières allumées dans la chambre.",
        "Au revoir !",
    ]  # nothing after goodbye


def test_chat_debug_shows_the_intent_and_entities(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    _, replies, other, _ = _chat(["--lang", "fr", "--debug"], SAID, monkeypatch, capsys)
    assert len(other) == len(replies) == 4
    assert "control_device" in other[1] and "'room_entity': 'kitchen'" in other[1]


def test_chat_with_a_missing_dm_folder_is_a_one_line_error(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["chat", "--dm", str(tmp_path / "none")]) == 2
    assert "no such directory" in capsys.readouterr().err
