"""``amiro chat``: a terminal conversation with the dialogue manager (offline sources), typed
or, with ``--voice``, through the microphone (Silero VAD endpointing, then the configured
recogniser: Whisper in en, fr and ro by default)."""

from __future__ import annotations

import sys
from collections.abc import Iterator
from pathlib import Path

from amiro.core.config import ConfigError
from amiro.dialogue.actions import Actions
from amiro.dialogue.domain import load_dm
from amiro.dialogue.manager import DialogueManager
from amiro.dialogue.phrases import phrase
from amiro.dialogue.sources import offline_sources
from amiro.dialogue.understanding import Nlu

PROMPT = "you> "


def _typed() -> Iterator[str]:
    while True:
        try:
            line = input(PROMPT)
        except EOFError:
            return
        yield line


def _spoken(lang: str) -> Iterator[str]:
    import numpy as np

    from amiro.dialogue.audio import ASR_RATE, Audio
    from amiro.dialogue.config import DialogueConfig
    from amiro.dialogue.silero import SileroEndpointer
    from amiro.dialogue.stack import make_recognizer

    try:
        import sounddevice  # type: ignore[import-untyped,import-not-found,unused-ignore]
    except (ImportError, OSError):
        raise ConfigError(
            "chat --voice: needs the extra amiro[speech] (sounddevice) and PortAudio"
        ) from None
    recognizer = make_recognizer(DialogueConfig(), lang=lang)  # rejects what it misheard
    endpointer = SileroEndpointer()
    chunk = ASR_RATE // 10
    with sounddevice.RawInputStream(samplerate=ASR_RATE, channels=1, dtype="int16") as stream:
        print(phrase("chat_listening", lang), file=sys.stderr)
        while True:
            data, _ = stream.read(chunk)
            samples = np.frombuffer(bytes(data), dtype="<i2").copy()
            for utterance in endpointer.feed(Audio(samples, ASR_RATE)):
                heard = recognizer.transcribe(utterance)
                reason = heard.rejected or "..."
                shown = heard.text or phrase("chat_not_understood", lang, {"reason": reason})
                print(f"{PROMPT}{shown}")
                yield heard.text


def run_chat(lang: str, voice: bool, debug: bool = False, dm: Path | None = None) -> int:
    """Only the robot's reply is shown; ``debug`` adds the intent and entities understood;
    ``dm``: a folder of the user's own stories, rules and domain (``dialogue.dm``)."""
    domain, stories = load_dm(dm)
    nlu = Nlu()
    nlu.model(lang)  # train before the first prompt
    print(phrase("chat_banner", lang), file=sys.stderr)
    got: list[tuple[str, dict[str, object]]] = []
    actions = Actions(offline_sources(), lambda k, p: got.append((k, p)))
    manager = DialogueManager(nlu, domain, actions, stories=stories)
    try:
        for text in _spoken(lang) if voice else _typed():
            if not text.strip() and not voice:  # spoken but rejected: "did not understand"
                continue
            answer = manager.handle(text, lang, "user")
            shown = " [display]" if answer.display and not answer.say else ""
            print(f"robot> {answer.text}{shown}")
            if debug:
                print(f"       ({answer.intent} {answer.entities})")
            if answer.action == "utter_goodbye":
                break
    except KeyboardInterrupt:
        pass
    return 0
