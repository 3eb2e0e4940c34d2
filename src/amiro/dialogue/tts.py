"""Text to speech behind one interface: espeak-ng (en, ro, fr) by default; Piper with a
user-supplied voice and Google Cloud TTS as optional extras, each failing with a clear
one-line error when it cannot run."""

from __future__ import annotations

import shutil
import subprocess
from typing import TYPE_CHECKING, Protocol

from amiro.core.config import ConfigError
from amiro.dialogue.audio import Audio, read_wav_bytes

if TYPE_CHECKING:
    from amiro.dialogue.config import TtsConfig

ESPEAK_VOICES = {"en": "en-us", "ro": "ro", "fr": "fr-fr"}


class Synthesizer(Protocol):
    def synthesize(
        self, text: str, lang: str, voice: str = "", words_per_minute: int = 150
    ) -> Audio: ...


class EspeakSynthesizer:
    def __init__(self, executable: str = "espeak-ng") -> None:
        found = shutil.which(executable)
        if found is None:
            raise ConfigError(f"tts: {executable} not found (apt-get install espeak-ng)")
        self.executable = found

    def synthesize(
        self, text: str, lang: str, voice: str = "", words_per_minute: int = 150
    ) -> Audio:
        voice = voice or ESPEAK_VOICES.get(lang, lang)
        cmd = [self.executable, "-v", voice, "-s", str(words_per_minute), "--stdout", text]
        done = subprocess.run(cmd, capture_output=True, check=False, timeout=30)
        if done.returncode != 0 or not done.stdout:
            problem = done.stderr.decode(errors="replace").strip().splitlines()
            raise ConfigError(f"tts: espeak-ng failed: {problem[0] if problem else 'no audio'}")
        return read_wav_bytes(done.stdout, "espeak-ng output")


def espeak_synthesizer(cfg: TtsConfig) -> Synthesizer:
    return EspeakSynthesizer()
