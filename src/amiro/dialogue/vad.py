"""Voice activity and end-of-utterance detection for streaming audio, with pocketsphinx's
WebRTC-style endpointer: feed frames, get each finished utterance once its speaker stops."""

from __future__ import annotations

from collections.abc import Iterable, Iterator

import numpy as np
from pocketsphinx import Endpointer  # type: ignore[import-untyped,import-not-found,unused-ignore]

from amiro.dialogue.audio import ASR_RATE, Audio, resample


class UtteranceDetector:
    def __init__(self, window_s: float = 0.3, ratio: float = 0.9) -> None:
        self.endpointer = Endpointer(window=window_s, ratio=ratio, sample_rate=ASR_RATE)
        self.frame_bytes: int = self.endpointer.frame_bytes
        self._speech = bytearray()

    def feed(self, frame: bytes) -> Audio | None:
        """One frame of 16 kHz 16-bit audio (``frame_bytes`` long); an utterance when one ends."""
        was_speaking = self.endpointer.in_speech
        speech = self.endpointer.process(frame)
        if speech is not None:
            self._speech += speech
        if was_speaking and not self.endpointer.in_speech:
            return self._flush()
        return None

    def _flush(self) -> Audio | None:
        data, self._speech = bytes(self._speech), bytearray()
        return Audio(np.frombuffer(data, dtype="<i2").copy(), ASR_RATE) if data else None

    def finish(self) -> Audio | None:
        """End of stream: the utterance still open, if any."""
        if self.endpointer.in_speech:
            self._speech += self.endpointer.end_stream(b"\0" * self.frame_bytes) or b""
        return self._flush()


def utterances(audio: Audio | Iterable[Audio]) -> Iterator[Audio]:
    """Split a recording (or a stream of chunks) into utterances."""
    detector = UtteranceDetector()
    chunks = [audio] if isinstance(audio, Audio) else audio
    pending = b""
    for chunk in chunks:
        pending += resample(chunk, ASR_RATE).to_bytes()
        while len(pending) >= detector.frame_bytes:
            frame, pending = pending[: detector.frame_bytes], pending[detector.frame_bytes :]
            if (found := detector.feed(frame)) is not None:
                yield found
    if (last := detector.finish()) is not None:
        yield last
