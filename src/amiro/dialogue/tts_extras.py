"""Optional TTS engines: Piper (a user-supplied ``.onnx`` voice) and Google Cloud TTS."""

from __future__ import annotations

import io
import wave
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar

from amiro.core.config import ConfigError
from amiro.dialogue.audio import Audio, read_wav_bytes

if TYPE_CHECKING:
    from amiro.dialogue.config import TtsConfig


class PiperSynthesizer:
    def __init__(self, voice: Path | None = None) -> None:
        if voice is None or not Path(voice).is_file():
            raise ConfigError(f"tts piper: voice file not found: {voice} (set tts.piper_voice)")
        try:
            from piper import PiperVoice  # type: ignore[import-untyped,import-not-found,unused-ignore]
        except ImportError:
            raise ConfigError("tts piper: pip install piper-tts") from None
        self.voice: Any = PiperVoice.load(str(voice))

    def synthesize(
        self, text: str, lang: str, voice: str = "", words_per_minute: int = 150
    ) -> Audio:
        buffer = io.BytesIO()
        with wave.open(buffer, "wb") as w:
            self.voice.synthesize_wav(text, w)
        return read_wav_bytes(buffer.getvalue(), "piper output")


class GoogleSynthesizer:
    """Google Cloud Text-to-Speech, the paper's engine; needs application credentials."""

    LANGUAGE_CODES: ClassVar[dict[str, str]] = {"en": "en-US", "ro": "ro-RO", "fr": "fr-FR"}

    def __init__(self) -> None:
        try:
            from google.cloud import texttospeech  # type: ignore[import-untyped,import-not-found,unused-ignore]
        except ImportError:
            raise ConfigError("tts google: pip install google-cloud-texttospeech") from None
        try:
            self.client: Any = texttospeech.TextToSpeechClient()
        except Exception as exc:
            raise ConfigError(f"tts google: no usable credentials ({type(exc).__name__})") from None
        self.api: Any = texttospeech

    def synthesize(
        self, text: str, lang: str, voice: str = "", words_per_minute: int = 150
    ) -> Audio:
        api = self.api
        response = self.client.synthesize_speech(
            input=api.SynthesisInput(text=text),
            voice=api.VoiceSelectionParams(language_code=self.LANGUAGE_CODES.get(lang, lang)),
            audio_config=api.AudioConfig(audio_encoding=api.AudioEncoding.LINEAR16),
        )
        return read_wav_bytes(response.audio_content, "google tts output")


def piper_synthesizer(cfg: TtsConfig) -> PiperSynthesizer:
    return PiperSynthesizer(cfg.piper_voice)


def google_synthesizer(cfg: TtsConfig) -> GoogleSynthesizer:
    return GoogleSynthesizer()
