"""The microphone topic heard in process: the simulated residents' replies voiced onto
/amiro/audio, cut by the streaming endpointer, recognised on a worker thread and published
as transcripts no earlier than the end of their audio, in the language the robot spoke."""

from __future__ import annotations

import threading
import time

import numpy as np

from amiro.core import names
from amiro.core.clock import SimClock
from amiro.core.messages import AudioStamped, Header, SpeechHeard, SpeechRequest
from amiro.core.runtime import Runtime
from amiro.dialogue.asr import Transcript
from amiro.dialogue.audio import Audio
from amiro.dialogue.config import DialogueConfig
from amiro.dialogue.profiles import SpeakerProfile
from amiro.dialogue.recognizer_node import RecognizerNode
from amiro.dialogue.stack import add_microphone, add_recognizer
from amiro.dialogue.text import normalize
from amiro.dialogue.tts import EspeakSynthesizer

PROFILES = {"maria": SpeakerProfile(lang="en"), "ion": SpeakerProfile(lang="ro")}


def _heard(runtime: Runtime) -> list[tuple[float, SpeechHeard]]:
    got: list[tuple[float, SpeechHeard]] = []
    runtime.bus.subscribe(
        names.HEARD, SpeechHeard, lambda m: got.append((runtime.clock.now(), m)), 10
    )
    return got


def test_a_voiced_reply_is_heard_by_whisper_when_it_ends() -> None:
    runtime = Runtime(SimClock())
    recognizer = add_recognizer(runtime, DialogueConfig(), PROFILES, wait=True)
    assert set(recognizer.recognizers) == {
        (lang, g) for lang in ("en", "ro") for g in ("answers", "nlu")
    }  # built, the model loaded, before anything is heard
    microphone = add_microphone(runtime, DialogueConfig(), PROFILES)
    runtime.start()
    got = _heard(runtime)
    runtime.bus.publish(names.SAY, SpeechRequest("Maria, please drink.", "en", addressee="maria"))
    runtime.spin_for(1.0)
    reply = SpeechHeard("yes, I will drink a glass of water now", "en", "maria", intent="affirm")
    runtime.bus.publish(names.HEARD, reply)
    runtime.spin_for(8.0)
    recognised = [(t, h) for t, h in got if h.intent is None]
    assert len(recognised) == 1 and len(microphone.voiced) == 1
    at, heard = recognised[0]
    assert {"yes", "glass", "water"} <= set(normalize(heard.text).split())
    assert heard.lang == "en" and heard.speaker is None and heard.confidence >= 0.5
    spoken = microphone.voiced[0][1]
    assert at >= 1.0 + spoken  # not before the resident finished speaking
    assert recognizer.heard[0]["grammar"] == "answers" and recognizer.heard[0]["published"] == at


class HeldRecognizer:
    """Recognises only once released, in the language it was built for."""

    def __init__(self, lang: str, release: threading.Event) -> None:
        self.lang = lang
        self.release = release

    def transcribe(self, audio: Audio) -> Transcript:
        self.release.wait(10.0)
        return Transcript(f"{self.lang}:{audio.seconds:.1f}", 0.9)


def test_without_waiting_the_transcript_comes_when_ready_and_follows_the_robots_language() -> None:
    release = threading.Event()
    runtime = Runtime(SimClock())
    node = runtime.add(
        RecognizerNode(lambda lang, g: HeldRecognizer(lang, release), ["en", "ro"], "en")
    )
    runtime.start()
    got = _heard(runtime)
    runtime.bus.publish(names.SAY, SpeechRequest("Ion, ai băut apă?", "ro", addressee="ion"))
    speech = EspeakSynthesizer().synthesize("da, beau acum un pahar cu apă", "ro")
    silence = np.zeros(speech.rate, np.int16)
    samples = np.concatenate([speech.samples, silence])
    runtime.bus.publish(names.AUDIO, AudioStamped(Header(0.0, "mic"), samples, speech.rate))
    runtime.spin_for(len(samples) / speech.rate + 2.0)
    assert got == []  # the audio has ended, the recogniser has not
    release.set()
    for _ in range(1000):  # the worker thread finishes in wall time
        if got:
            break
        runtime.spin_for(0.05)
        time.sleep(0.01)
    assert len(got) == 1 and got[0][1].lang == "ro" and got[0][1].text.startswith("ro:")
    assert node.heard[0]["grammar"] == "answers"
