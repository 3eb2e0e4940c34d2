"""Speech output on the bus: publishes what to say; a TTS node or the robot voices it."""

from __future__ import annotations

from amiro.core import names
from amiro.core.bus import Bus
from amiro.core.messages import SpeechRequest


def speaking_time(text: str, words_per_second: float = 2.5) -> float:
    """How long a voice takes to say ``text``: about 150 words a minute plus a lead-in."""
    return 0.4 + len(text.split()) / words_per_second


class BusSpeechOutput:
    """Publishes ``SpeechRequest`` and estimates the speaking time (about 150 words/min)."""

    def __init__(self, bus: Bus, words_per_second: float = 2.5) -> None:
        self.pub = bus.publisher(names.SAY, SpeechRequest)
        self.words_per_second = words_per_second

    def say(self, text: str, lang: str, act: str = "", addressee: str = "") -> float:
        self.pub.publish(SpeechRequest(text=text, lang=lang, act=act, addressee=addressee))
        return speaking_time(text, self.words_per_second)
