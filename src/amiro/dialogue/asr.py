"""Speech recognition behind one interface: pocketsphinx (its bundled English model, JSGF
grammar or the free language model), Vosk for a user-supplied model, Google Cloud Speech."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

from amiro.core.registry import register
from amiro.dialogue.audio import Audio

register("asr", "pocketsphinx", "amiro.dialogue.asr_pocketsphinx:PocketsphinxRecognizer")
register("asr", "vosk", "amiro.dialogue.asr_extras:VoskRecognizer")
register("asr", "google", "amiro.dialogue.asr_extras:GoogleRecognizer")


@dataclass(frozen=True)
class Transcript:
    text: str
    confidence: float = 1.0


class Recognizer(Protocol):
    def transcribe(self, audio: Audio) -> Transcript: ...
