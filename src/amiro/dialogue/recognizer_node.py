"""Hearing a microphone topic: the audio on ``/amiro/audio`` (a real robot's driver, or the
simulator's :class:`~amiro.dialogue.microphone.SimMicrophone`) cut into utterances by the
streaming Silero endpointer, each recognised, and its transcript published on
``/amiro/speech/heard`` with its confidence and language for Listen and the dialogue.

The recognisers (one Whisper model under all of them) are built with the node, so the model
loads when the process starts, not at the first utterance.  Recognition runs on a worker
thread while the executor goes on (the robot keeps moving, the resident may still be
speaking in simulated time); a transcript is published once it is ready and no earlier than
the end of its audio.  ``wait`` makes the executor wait for it at that moment instead: a
simulated run on its own clock then hears every utterance at the same simulated time, run
after run.

The language listened for is the one the robot last spoke (``/amiro/say``), since the
residents answer in the language they are addressed in; a question to someone (a
``SpeechRequest`` with an addressee, as Listen's prompts are) is answered with Listen's
yes/no/later prompt, anything else with the household's command prompt."""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import dataclass
from functools import partial
from typing import Any

from amiro.core import names
from amiro.core.messages import AudioStamped, SpeechHeard, SpeechRequest
from amiro.core.node import Node
from amiro.dialogue.asr import Recognizer, Transcript
from amiro.dialogue.audio import Audio
from amiro.dialogue.silero import SileroEndpointer

GRAMMARS = ("answers", "nlu")


@dataclass
class Utterance:
    audio: Audio
    lang: str
    grammar: str
    ends: float  # sim time at which the microphone had delivered it
    result: Future[tuple[Transcript, float]]


class RecognizerNode(Node):
    def __init__(
        self,
        recognizer_for: Callable[[str, str], Recognizer],
        langs: Iterable[str],
        lang: str,
        wait: bool = False,
        poll_s: float = 0.05,
    ) -> None:
        super().__init__("recognizer")
        self.langs = tuple(dict.fromkeys((lang, *langs)))
        self.recognizers = {(la, g): recognizer_for(la, g) for la in self.langs for g in GRAMMARS}
        self.lang = lang
        self.grammar = "nlu"
        self.wait = wait
        self.poll_s = poll_s
        self.heard: list[dict[str, Any]] = []  # what was recognised, for reports and tests

    def on_start(self) -> None:
        self.endpointer = SileroEndpointer()
        self.worker = ThreadPoolExecutor(1, thread_name_prefix="recognizer")
        self.pub = self.create_publisher(names.HEARD, SpeechHeard)
        self.create_subscription(names.SAY, SpeechRequest, self._on_say, 10)
        self.create_subscription(names.AUDIO, AudioStamped, self._on_audio, 500)

    def on_stop(self) -> None:
        self.worker.shutdown(wait=False, cancel_futures=True)

    def _on_say(self, msg: SpeechRequest) -> None:
        if msg.say and msg.lang in self.langs:
            self.lang = msg.lang
            self.grammar = "answers" if msg.addressee else "nlu"

    def _on_audio(self, msg: AudioStamped) -> None:
        ends = msg.header.stamp + msg.seconds
        for audio in self.endpointer.feed(Audio(msg.samples, msg.rate)):
            recognizer = self.recognizers[(self.lang, self.grammar)]
            result = self.worker.submit(_recognise, recognizer, audio)
            utterance = Utterance(audio, self.lang, self.grammar, ends, result)
            self.call_later(ends - self.now(), partial(self._deliver, utterance))

    def _deliver(self, u: Utterance) -> None:
        if not (u.result.done() or self.wait):
            self.call_later(self.poll_s, partial(self._deliver, u))
            return
        transcript, seconds = u.result.result()
        self.heard.append(
            {
                "lang": u.lang,
                "grammar": u.grammar,
                "text": transcript.text,
                "rejected": transcript.rejected,
                "confidence": round(transcript.confidence, 3),
                "speech_s": round(u.audio.seconds, 2),
                "recognition_s": round(seconds, 2),  # wall time, for reports only
                "ended": round(u.ends, 2),
                "published": round(self.now(), 2),
            }
        )
        self.pub.publish(SpeechHeard(transcript.text, u.lang, confidence=transcript.confidence))


def _recognise(recognizer: Recognizer, audio: Audio) -> tuple[Transcript, float]:
    start = time.perf_counter()
    transcript = recognizer.transcribe(audio)
    return transcript, time.perf_counter() - start
