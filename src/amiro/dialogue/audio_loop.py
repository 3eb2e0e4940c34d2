"""Real audio in the simulator: the resident's English reply text is voiced with espeak-ng
and recognised by pocketsphinx (yes/no/later grammar) before the NLU sees it, so Listen runs
on what the recogniser heard, not on the simulator's text."""

from __future__ import annotations

from dataclasses import replace

from amiro.core.messages import SpeechHeard
from amiro.dialogue.asr import Recognizer
from amiro.dialogue.audio import preprocess
from amiro.dialogue.profiles import SpeakerProfile
from amiro.dialogue.tts import Synthesizer
from amiro.dialogue.understanding import Nlu


class AudioLoopUnderstanding:
    def __init__(
        self,
        nlu: Nlu,
        synthesizer: Synthesizer,
        recognizer: Recognizer,
        profiles: dict[str, SpeakerProfile],
    ) -> None:
        self.nlu = nlu
        self.synthesizer = synthesizer
        self.recognizer = recognizer
        self.profiles = profiles
        self.heard: list[tuple[str, str]] = []  # (said, recognised), for reports and tests

    def intent(self, heard: SpeechHeard) -> tuple[str, float]:
        if heard.lang != "en":
            return self.nlu.intent(heard)
        profile = self.profiles.get(heard.speaker or "") or SpeakerProfile()
        audio = self.synthesizer.synthesize(
            heard.text, "en", profile.voice, profile.words_per_minute
        )
        audio = preprocess(audio, profile.gain_db, profile.highpass_hz)
        transcript = self.recognizer.transcribe(audio)
        self.heard.append((heard.text, transcript.text))
        recognised = replace(heard, text=transcript.text, confidence=transcript.confidence)
        return self.nlu.intent(recognised)
