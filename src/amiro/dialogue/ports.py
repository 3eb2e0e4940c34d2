"""The dialogue ports that tasks use: speaking and understanding an answer."""

from __future__ import annotations

from typing import Protocol

from amiro.core.messages import SpeechHeard


class SpeechOutput(Protocol):
    def say(self, text: str, lang: str, act: str = "", addressee: str = "") -> float:
        """Start saying ``text``; returns how long it takes, in seconds."""
        ...


class Understanding(Protocol):
    def intent(self, heard: SpeechHeard) -> tuple[str, float]:
        """The intent of an utterance and a confidence in [0, 1]."""
        ...
