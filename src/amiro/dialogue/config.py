"""Configuration of the dialogue stack: which NLU, TTS and ASR backends, and user profiles."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Literal

from pydantic import Field

from amiro.core.config import Section
from amiro.core.registry import backend_name
from amiro.dialogue import backends as _backends  # noqa: F401 - registers the names
from amiro.dialogue.asr import DEFAULT_LISTEN_REJECT_BELOW, DEFAULT_REJECT_BELOW
from amiro.dialogue.nlu import DEFAULT_THRESHOLD
from amiro.dialogue.profiles import SpeakerProfile


class TtsConfig(Section):
    backend: Annotated[str, backend_name("tts")] = "espeak"
    output: Literal["none", "wav", "speaker"] = Field(
        default="none", description="none: the robot (or simulator) voices /amiro/say itself"
    )
    wav_dir: Path = Path("amiro-tts")
    piper_voice: Path | None = None


class AsrConfig(Section):
    backend: Annotated[str, backend_name("asr")] = "pocketsphinx"
    grammar: Literal["nlu", "answers", "none"] = Field(
        default="nlu",
        description="pocketsphinx search: JSGF from the NLU data, yes/no/later, or LM",
    )
    reject_below: float = Field(
        default=DEFAULT_REJECT_BELOW,
        ge=0.0,
        le=1.0,
        description="commands with a lower confidence are rejected (heard as not understood)",
    )
    listen_reject_below: float = Field(
        default=DEFAULT_LISTEN_REJECT_BELOW,
        ge=0.0,
        le=1.0,
        description="the same for answers to the robot's questions (Listen, answers grammar)",
    )
    vosk_model: Path | None = None
    sim_audio: bool = Field(
        default=False,
        description="in the simulator, voice English replies with espeak-ng and recognise them",
    )


class DialogueConfig(Section):
    nlu: Annotated[str, backend_name("nlu")] = "amiro"
    nlu_threshold: float = Field(default=DEFAULT_THRESHOLD, ge=0.0, le=1.0)
    training_data: dict[Literal["en", "ro", "fr"], Path] = Field(
        default_factory=dict, description="language -> Rasa-style YAML replacing the shipped data"
    )
    dm: Path | None = Field(
        default=None,
        description="a folder laid out like data/dialogue/dm (domain.yml, rules.yml, "
        "stories.yml, stories.<lang>.yml) replacing amiro's files it holds",
    )
    words_per_second: float = Field(default=2.5, gt=0.0)
    tts: TtsConfig = Field(default_factory=TtsConfig)
    asr: AsrConfig = Field(default_factory=AsrConfig)
    profiles: dict[str, SpeakerProfile] = Field(default_factory=dict)
