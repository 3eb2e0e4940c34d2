"""The simulated residents speak: each reply the simulator hands over as text is voiced with
espeak-ng in the resident's language and voice (and the profile's gain and high-pass), then
recognised by the recogniser of that language before the NLU sees it, so Listen runs on what
the recogniser heard, not on the simulator's text (``dialogue.hearing: audio``).

Only the simulator's replies are voiced: they are the only :class:`SpeechHeard` that carry an
intent label (its oracle); what a real microphone's recogniser publishes goes straight to the
NLU.  One recogniser per language of the household, built with the system (the Whisper model
under them is loaded then, once per process, 1-5 s on this 2-core machine), as the NLU is
warmed up then: a run is not slowed by loading when its first reply is heard."""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterable
from dataclasses import replace

from amiro.core.messages import SpeechHeard
from amiro.dialogue.asr import Recognizer
from amiro.dialogue.understanding import Nlu
from amiro.dialogue.voicing import Voicer


class AudioLoopUnderstanding:
    def __init__(
        self,
        nlu: Nlu,
        voicer: Voicer,
        recognizer_for: Callable[[str], Recognizer],
        langs: Iterable[str] = (),
    ) -> None:
        self.nlu = nlu
        self.voicer = voicer
        self.recognizer_for = recognizer_for
        self.recognizers: dict[str, Recognizer] = {}
        self._lock = threading.Lock()
        self.heard: list[tuple[str, str]] = []  # (said, recognised), for reports and tests
        for lang in langs:  # now, not at the first reply (another language: when heard)
            self.recognizer(lang)

    def recognizer(self, lang: str) -> Recognizer:
        with self._lock:
            if lang not in self.recognizers:
                self.recognizers[lang] = self.recognizer_for(lang)
            return self.recognizers[lang]

    def intent(self, heard: SpeechHeard) -> tuple[str, float]:
        if heard.intent is None:  # a real recogniser's result: already heard
            return self.nlu.intent(heard)
        transcript = self.recognizer(heard.lang).transcribe(self.voicer.voice(heard))
        self.heard.append((heard.text, transcript.text))
        recognised = replace(
            heard, text=transcript.text, confidence=transcript.confidence, intent=None
        )
        return self.nlu.intent(recognised)
