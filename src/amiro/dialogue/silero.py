"""Voice activity with the Silero VAD model that the faster-whisper wheel ships
(``faster_whisper/assets/silero_vad_v6.onnx``, MIT): speech probabilities per 32 ms window,
whether a clip holds speech at all, and streaming end-of-utterance detection for the
microphone.  The network is recurrent; its state is carried from one chunk to the next, so
a stream gives the same probabilities as the whole recording at once."""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from amiro.core.config import ConfigError
from amiro.dialogue.audio import ASR_RATE, Audio, resample

WINDOW = 512  # samples a probability (32 ms at 16 kHz)
CONTEXT = 64  # samples of the previous window the model sees with each window
SPEECH_ABOVE = 0.5  # Silero's usual threshold
MIN_SPEECH_S = 0.15  # less than this much speech is a click, not an utterance


@cache
def _session() -> Any:
    try:
        import onnxruntime
        from faster_whisper.utils import get_assets_path
    except ImportError:
        raise ConfigError("vad: needs the extra amiro[speech] (faster-whisper)") from None
    path = Path(get_assets_path()) / "silero_vad_v6.onnx"
    opts = onnxruntime.SessionOptions()
    opts.inter_op_num_threads = 1
    opts.intra_op_num_threads = 1
    opts.log_severity_level = 4
    return onnxruntime.InferenceSession(
        str(path), providers=["CPUExecutionProvider"], sess_options=opts
    )


def as_float(audio: Audio) -> npt.NDArray[np.float32]:
    """16 kHz samples in [-1, 1], the form Silero and Whisper take."""
    return (resample(audio, ASR_RATE).samples.astype(np.float32) / 32768.0).astype(np.float32)


@dataclass
class SileroVad:
    """Speech probability per window; call :meth:`probs` on consecutive chunks of a stream."""

    _h: npt.NDArray[np.float32] = field(default_factory=lambda: np.zeros((1, 1, 128), np.float32))
    _c: npt.NDArray[np.float32] = field(default_factory=lambda: np.zeros((1, 1, 128), np.float32))
    _context: npt.NDArray[np.float32] = field(default_factory=lambda: np.zeros(CONTEXT, np.float32))
    _pending: npt.NDArray[np.float32] = field(default_factory=lambda: np.zeros(0, np.float32))

    def probs(self, x: npt.NDArray[np.float32]) -> npt.NDArray[np.float32]:
        """Probabilities of the whole windows completed by ``x`` (the rest waits)."""
        x = np.concatenate([self._pending, x])
        n = len(x) // WINDOW
        self._pending = x[n * WINDOW :]
        if n == 0:
            return np.zeros(0, np.float32)
        windows = x[: n * WINDOW].reshape(n, WINDOW)
        previous = np.concatenate([self._context[None, :], windows[:-1, -CONTEXT:]])
        batch = np.concatenate([previous, windows], axis=1)
        self._context = windows[-1, -CONTEXT:].copy()
        out, self._h, self._c = _session().run(None, {"input": batch, "h": self._h, "c": self._c})
        return np.asarray(out, np.float32).reshape(-1)


def speech_span(audio: Audio, pad_s: float = 0.2) -> tuple[int, int] | None:
    """First and last sample (16 kHz) of speech, padded; None when the clip has no speech."""
    x = as_float(audio)
    padded = np.pad(x, (0, (-len(x)) % WINDOW))
    speech = np.flatnonzero(SileroVad().probs(padded) >= SPEECH_ABOVE)
    if len(speech) * WINDOW < MIN_SPEECH_S * ASR_RATE:
        return None
    pad = int(pad_s * ASR_RATE)
    return max(0, int(speech[0]) * WINDOW - pad), min(len(x), (int(speech[-1]) + 1) * WINDOW + pad)


class SileroEndpointer:
    """Streaming end of utterance: an utterance ends after ``silence_s`` without speech."""

    def __init__(self, silence_s: float = 0.6, pad_s: float = 0.2, max_s: float = 25.0) -> None:
        self.vad = SileroVad()
        self.silence_windows = int(silence_s * ASR_RATE / WINDOW)
        self.pad = int(pad_s * ASR_RATE / WINDOW)
        self.max_windows = int(max_s * ASR_RATE / WINDOW)
        self._windows: list[npt.NDArray[np.float32]] = []  # since a little before speech
        self._speech = 0  # speech windows in the open utterance
        self._quiet = 0  # windows since the last speech
        self._buffer = np.zeros(0, np.float32)

    def feed(self, chunk: Audio) -> list[Audio]:
        """Any length of audio; the utterances it completes."""
        x = np.concatenate([self._buffer, as_float(chunk)])
        n = len(x) // WINDOW
        self._buffer = x[n * WINDOW :]
        windows = x[: n * WINDOW].reshape(n, WINDOW)
        done = []
        for window, p in zip(windows, self.vad.probs(windows.reshape(-1)), strict=True):
            if (ended := self._step(window, p >= SPEECH_ABOVE)) is not None:
                done.append(ended)
        return done

    def _step(self, window: npt.NDArray[np.float32], speech: bool) -> Audio | None:
        self._windows.append(window)
        if speech:
            self._speech, self._quiet = self._speech + 1, 0
        else:
            self._quiet += 1
        if not self._speech:
            self._windows = self._windows[-self.pad :]  # keep a little lead-in only
            return None
        if self._quiet >= self.silence_windows or len(self._windows) >= self.max_windows:
            return self.finish()
        return None

    def finish(self) -> Audio | None:
        """End of stream (or of the utterance): the speech collected, if any."""
        keep = self._speech * WINDOW >= MIN_SPEECH_S * ASR_RATE
        tail = max(0, self._quiet - self.pad)
        windows = self._windows[: len(self._windows) - tail]
        self._windows, self._speech, self._quiet = [], 0, 0
        if not keep or not windows:
            return None
        x = np.concatenate(windows)
        return Audio(np.clip(np.round(x * 32768.0), -32768, 32767).astype(np.int16), ASR_RATE)


def utterances(chunks: Iterable[Audio]) -> Iterator[Audio]:
    """The utterances of a stream of chunks (a microphone, a ROS 2 audio topic)."""
    endpointer = SileroEndpointer()
    for chunk in chunks:
        yield from endpointer.feed(chunk)
    if (last := endpointer.finish()) is not None:
        yield last
