"""Configuration of the dialogue stack: which NLU, TTS and ASR backends, and user profiles."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Literal

from pydantic import Field

from amiro.core.config import Section
from amiro.core.registry import backend_name
from amiro.dialogue import backends as _backends  # noqa: F401 - registers the names
from amiro.dialogue.asr import DEFAULT_REJECT_BELOW, LISTEN_REJECT_BELOW
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
    backend: Annotated[str, backend_name("asr")] = "whisper"
    grammar: Literal["nlu", "answers", "none"] = Field(
        default="nlu",
        description="what commands are expected: the NLU's (pocketsphinx: its JSGF; whisper: "
        "its prompt), yes/no/later, or anything (pocketsphinx's LM, no prompt)",
    )
    reject_below: float = Field(
        default=DEFAULT_REJECT_BELOW,
        ge=0.0,
        le=1.0,
        description="commands with a lower confidence are rejected (heard as not understood)",
    )
    listen_reject_below: float | None = Field(
        default=None,
        ge=0.0,
        le=1.0,
        description="the same for answers to the robot's questions (Listen, answers grammar); "
        "default: the backend's (pocketsphinx 0, others as reject_below)",
    )
    vosk_model: Path | None = None
    whisper_model: Path | None = Field(
        default=None,
        description="a CTranslate2 Whisper directory (small, medium ...); default: the "
        "packaged Whisper base of the speech extra",
    )
    whisper_threads: int = Field(default=2, ge=1, description="CPU threads for Whisper")
    whisper_compute_type: Literal["int8", "int8_float32", "float32"] = "int8"
    whisper_beam_size: int = Field(default=1, ge=1, le=10)
    vocabulary: list[str] = Field(
        default_factory=list,
        description="names Whisper's prompt mentions besides the rooms and commands (the "
        "household's names are added by the system)",
    )

    @property
    def listen_threshold(self) -> float:
        """``listen_reject_below``, else the backend's default for Listen."""
        if self.listen_reject_below is not None:
            return self.listen_reject_below
        return LISTEN_REJECT_BELOW.get(self.backend, self.reject_below)


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
    hearing: Literal["audio", "text-oracle"] = Field(  # one process; split: hear_audio
        default="audio",
        description="in the simulator: audio voices each resident's reply (espeak-ng, their "
        "language) into the recogniser of their language; text-oracle hands the NLU the "
        "reply's text (also the fallback, said once, without the speech extra)",
    )
    tts: TtsConfig = Field(default_factory=TtsConfig)
    asr: AsrConfig = Field(default_factory=AsrConfig)
    profiles: dict[str, SpeakerProfile] = Field(default_factory=dict)
