"""Optional recognisers: Vosk with a user-supplied model directory (any language) and Google
Cloud Speech, the paper's engine.  Each fails with a one-line error when it cannot run."""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar

from amiro.core.config import ConfigError
from amiro.dialogue.asr import Transcript
from amiro.dialogue.audio import ASR_RATE, Audio, resample

if TYPE_CHECKING:
    from amiro.dialogue.config import AsrConfig


class VoskRecognizer:
    def __init__(self, model: Path | None = None) -> None:
        if model is None or not (Path(model) / "conf").is_dir():
            raise ConfigError(
                f"asr vosk: {model} is not a Vosk model directory (set asr.vosk_model)"
            )
        try:
            import vosk  # type: ignore[import-untyped,import-not-found,unused-ignore]
        except ImportError:
            raise ConfigError("asr vosk: pip install vosk") from None
        vosk.SetLogLevel(-1)
        self.vosk: Any = vosk
        self.model: Any = vosk.Model(str(model))

    def transcribe(self, audio: Audio) -> Transcript:
        rec = self.vosk.KaldiRecognizer(self.model, ASR_RATE)
        rec.AcceptWaveform(resample(audio, ASR_RATE).to_bytes())
        return Transcript(str(json.loads(rec.FinalResult()).get("text", "")))


class GoogleRecognizer:
    LANGUAGE_CODES: ClassVar[dict[str, str]] = {"en": "en-US", "ro": "ro-RO", "fr": "fr-FR"}

    def __init__(self, lang: str = "en") -> None:
        try:
            from google.cloud import speech  # type: ignore[import-untyped,import-not-found,unused-ignore]
        except ImportError:
            raise ConfigError("asr google: pip install google-cloud-speech") from None
        try:
            self.client: Any = speech.SpeechClient()
        except Exception as exc:
            raise ConfigError(f"asr google: no usable credentials ({type(exc).__name__})") from None
        self.api: Any = speech
        self.lang = lang

    def transcribe(self, audio: Audio) -> Transcript:
        config = self.api.RecognitionConfig(
            encoding=self.api.RecognitionConfig.AudioEncoding.LINEAR16,
            sample_rate_hertz=ASR_RATE,
            language_code=self.LANGUAGE_CODES.get(self.lang, self.lang),
        )
        content = self.api.RecognitionAudio(content=resample(audio, ASR_RATE).to_bytes())
        response = self.client.recognize(config=config, audio=content)
        best = [r.alternatives[0] for r in response.results if r.alternatives]
        if not best:
            return Transcript("", 0.0)
        return Transcript(" ".join(a.transcript for a in best), float(best[0].confidence))


def vosk_recognizer(cfg: AsrConfig, grammar: str, lang: str) -> VoskRecognizer:
    return VoskRecognizer(cfg.vosk_model)


def google_recognizer(cfg: AsrConfig, grammar: str, lang: str) -> GoogleRecognizer:
    return GoogleRecognizer(lang)
