"""Per-resident speech settings (the paper's audio preprocessing, section 3.2): language,
voice and audio settings, so one household can mix languages and voices."""

from __future__ import annotations

from collections.abc import Iterable

from pydantic import Field

from amiro.core.config import Section
from amiro.home.household import Language, Person


class SpeakerProfile(Section):
    lang: Language = "en"
    voice: str = Field(default="", description="TTS voice; empty: the language's default")
    words_per_minute: int = Field(default=150, ge=60, le=400)
    gain_db: float = Field(default=0.0, ge=-30.0, le=30.0, description="applied before ASR")
    highpass_hz: float = Field(default=80.0, ge=0.0, le=1000.0, description="before ASR")


def language_of(profiles: dict[str, SpeakerProfile], speaker: str | None, fallback: str) -> str:
    profile = profiles.get(speaker or "")
    return profile.lang if profile is not None else fallback


def household_voices(people: Iterable[Person]) -> dict[str, SpeakerProfile]:
    """A profile per person of the household (language and voice), for people without a
    configured one."""
    return {p.name: SpeakerProfile(lang=p.language, voice=p.voice) for p in people}
