"""The speech and understanding backends the ``dialogue:`` section names (see
:mod:`amiro.core.registry`).

Each kind, the config field that names it, and how its factory is called:

- ``asr`` (``dialogue.asr.backend``): ``factory(cfg: AsrConfig, grammar: str, lang: str) ->
  Recognizer`` (``grammar``: the pocketsphinx search, nlu, answers or none).
- ``tts`` (``dialogue.tts.backend``): ``factory(cfg: TtsConfig) -> Synthesizer``.
- ``nlu`` (``dialogue.nlu``): ``factory(nlu: Nlu, cfg: DialogueConfig, profiles: dict[str,
  SpeakerProfile]) -> Understanding``, what Listen tasks understand replies with, given the
  household's NLU.

Vosk, Piper and Google's clients are in no amiro extra yet: their backends say which package
to install when it is missing.  Only names and import paths here: the config imports this.
"""

from __future__ import annotations

from amiro.core.registry import register

register(
    "asr", "pocketsphinx", "amiro.dialogue.asr_pocketsphinx:pocketsphinx_recognizer", extra="speech"
)
register("asr", "whisper", "amiro.dialogue.asr_whisper:whisper_recognizer", extra="speech")
register("asr", "vosk", "amiro.dialogue.asr_extras:vosk_recognizer")
register("asr", "google", "amiro.dialogue.asr_extras:google_recognizer")
register("tts", "espeak", "amiro.dialogue.tts:espeak_synthesizer")
register("tts", "piper", "amiro.dialogue.tts_extras:piper_synthesizer")
register("tts", "google", "amiro.dialogue.tts_extras:google_synthesizer")
register("nlu", "amiro", "amiro.dialogue.stack:amiro_understanding")
register("nlu", "oracle", "amiro.dialogue.stack:oracle_understanding")
