"""Speech recognition behind one interface: pocketsphinx (its bundled English model, JSGF
grammar or the free language model), Vosk for a user-supplied model, Google Cloud Speech."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

from amiro.dialogue.audio import Audio

# Both recognisers' confidences read 0.5 at their limits (asr_confidence, asr_whisper).
# pocketsphinx: replies to the robot's yes/no questions often run past the answers grammar
# ("sure, thank you, I'm drinking now"), which reads as unexplained speech, so its Listen
# rejects nothing by default (measured trade-off in docs/dialogue.md); Whisper transcribes
# such replies freely, so its Listen keeps the common threshold.
DEFAULT_REJECT_BELOW = 0.5
LISTEN_REJECT_BELOW = {"pocketsphinx": 0.0}


@dataclass(frozen=True)
class Transcript:
    text: str  # what was understood: "" for silence or a rejected guess
    confidence: float = 1.0
    rejected: str = ""  # the best guess when its confidence was too low, for logs and reports

    @property
    def guess(self) -> str:
        """The recogniser's best guess, accepted or not."""
        return self.text or self.rejected


class Recognizer(Protocol):
    def transcribe(self, audio: Audio) -> Transcript: ...


def gate(transcript: Transcript, reject_below: float) -> Transcript:
    """The transcript, or an empty one carrying the guess when its confidence is below
    ``reject_below``: the robot must not act on speech it did not understand."""
    if transcript.text and transcript.confidence < reject_below:
        return Transcript("", transcript.confidence, rejected=transcript.text)
    return transcript


class ConfidenceGate:
    """Any recogniser with :func:`gate` applied to its results."""

    def __init__(self, recognizer: Recognizer, reject_below: float) -> None:
        self.recognizer = recognizer
        self.reject_below = reject_below

    def transcribe(self, audio: Audio) -> Transcript:
        return gate(self.recognizer.transcribe(audio), self.reject_below)
