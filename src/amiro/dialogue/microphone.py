"""The simulated robot's microphone: what the simulated residents say, as audio on
``/amiro/audio`` (the topic a real robot's audio driver publishes), for a recogniser in
another process to hear (:class:`~amiro.dialogue.recognizer_node.RecognizerNode`).

Each reply (the simulator's labelled :class:`SpeechHeard` on ``source``) is voiced by the
:class:`~amiro.dialogue.voicing.Voicer` and published in chunks of ``chunk_s``, as an audio
driver does, followed by ``tail_s`` of silence so that the recogniser's endpointer hears the
utterance end.  Each chunk is stamped with the time its first sample is spoken (the first
when the resident starts), but all are handed over at once: the recogniser may work while the
resident is still speaking in simulated time, and publishes no transcript before the audio's
end.  The bus's subscription depth must hold an utterance's chunks (the recogniser's does)."""

from __future__ import annotations

import numpy as np

from amiro.core import names
from amiro.core.messages import AudioStamped, Header, SpeechHeard
from amiro.core.node import Node
from amiro.dialogue.voicing import Voicer

MIC_FRAME = "microphone"


class SimMicrophone(Node):
    def __init__(
        self,
        voicer: Voicer,
        source: str = names.HEARD,
        chunk_s: float = 0.5,
        tail_s: float = 1.0,
    ) -> None:
        super().__init__("sim_microphone")
        self.voicer = voicer
        self.source = source
        self.chunk_s = chunk_s
        self.tail_s = tail_s
        self.voiced: list[tuple[str, float]] = []  # (text, seconds of speech), for reports

    def on_start(self) -> None:
        self.pub = self.create_publisher(names.AUDIO, AudioStamped)
        self.create_subscription(self.source, SpeechHeard, self._on_reply, 10)

    def _on_reply(self, heard: SpeechHeard) -> None:
        if heard.intent is None:  # not a simulated resident's words
            return
        audio = self.voicer.voice(heard)
        self.voiced.append((heard.text, audio.seconds))
        tail = np.zeros(int(self.tail_s * audio.rate), np.int16)
        samples = np.concatenate([audio.samples, tail])
        step = max(1, int(self.chunk_s * audio.rate))
        start = self.now()
        for i in range(0, len(samples), step):
            header = Header(start + i / audio.rate, MIC_FRAME)
            self.pub.publish(AudioStamped(header, samples[i : i + step], audio.rate))
