"""A simulated resident's reply as the audio a microphone would pick up: espeak-ng in the
resident's language and voice, then the profile's high-pass and gain.

espeak-ng is deterministic (the same text, voice and rate give the same samples), so each
distinct reply is voiced once per process: a resident who says "yes" every hour is not
synthesised again."""

from __future__ import annotations

from functools import lru_cache

from amiro.core.messages import SpeechHeard
from amiro.dialogue.audio import Audio, preprocess
from amiro.dialogue.profiles import SpeakerProfile
from amiro.dialogue.tts import Synthesizer


class Voicer:
    def __init__(self, synthesizer: Synthesizer, profiles: dict[str, SpeakerProfile]) -> None:
        self.synthesizer = synthesizer
        self.profiles = profiles
        self._voice = lru_cache(maxsize=256)(self._synthesize)

    def voice(self, heard: SpeechHeard) -> Audio:
        profile = self.profiles.get(heard.speaker or "") or SpeakerProfile(lang=heard.lang)
        return self._voice(heard.text, heard.lang, profile)

    def _synthesize(self, text: str, lang: str, profile: SpeakerProfile) -> Audio:
        audio = self.synthesizer.synthesize(text, lang, profile.voice, profile.words_per_minute)
        return preprocess(audio, profile.gain_db, profile.highpass_hz)
