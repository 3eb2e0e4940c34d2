"""Whisper (faster-whisper / CTranslate2, packaged weights) as amiro's recogniser for
English, French and Romanian.

One utterance costs one encoder pass: the Silero VAD first drops clips without speech and
trims the silence around it; the speech is encoded once, the language detected from that
encoding and the transcript decoded from it, with the command-aware prompt of
:mod:`amiro.dialogue.asr_prompt`.  Whisper is trained on 30 s windows, but encoding only the
speech plus some silence (at least :data:`SHORT_WINDOW_S`) is 3-5 times faster on a 5 s
command (CTranslate2 takes shorter inputs); when the decoder then loops or runs past a
speaking rate (:data:`TOKENS_PER_S`), which measured on real recordings is how the short
window fails, the utterance is decoded again from the full 30 s window.

The confidence is the worst of three measures, each scaled so that its limit reads 0.5
(the recognisers' common rejection threshold, :data:`amiro.dialogue.asr.DEFAULT_REJECT_BELOW`):

- the average log-probability of the decoded tokens (limit :data:`LOGPROB_LIMIT`, Whisper's
  own fallback threshold): mumbling, noise read as words;
- the no-speech probability (limit :data:`NO_SPEECH_LIMIT`, Whisper's): non-speech;
- the probability of another language, when Whisper's language identification ranks one
  first (limit :data:`FOREIGN_LIMIT`): speech in another language, which Whisper would
  otherwise translate into the expected one ("les lumières sont très belles" comes out as
  "the lights are very beautiful" from the English recogniser).  Only past
  :data:`LID_MIN_S` of speech: on a word or two the identification is a guess (a Romanian
  "da" or "nu" ranks English first).
"""

from __future__ import annotations

import gzip
import math
import re
from dataclasses import dataclass
from itertools import pairwise
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt
from faster_whisper.audio import pad_or_trim
from faster_whisper.tokenizer import Tokenizer
from faster_whisper.transcribe import get_suppressed_tokens

from amiro.core.config import ConfigError
from amiro.dialogue.asr import Transcript
from amiro.dialogue.asr_prompt import prompt_for
from amiro.dialogue.audio import Audio
from amiro.dialogue.silero import as_float, speech_span
from amiro.dialogue.whisper_model import check_model_dir, load_whisper, packaged_model

if TYPE_CHECKING:
    from amiro.dialogue.config import AsrConfig

LANGUAGES = ("en", "fr", "ro")
LOGPROB_LIMIT = -1.0
NO_SPEECH_LIMIT = 0.6
FOREIGN_LIMIT = 0.6
LID_MIN_S = 1.0
COMPRESSION_LIMIT = 2.4  # Whisper's: above it the "transcript" is a loop of repeated words
WINDOW_S = 30.0
SHORT_WINDOW_S = 10.0
TAIL_S = 2.0  # silence encoded after the speech in the short window
TOKENS_PER_S = 6.0  # above any speaking rate (about 2-4 words, 3-5 tokens a second)
FRAMES_PER_S = 100


@dataclass(frozen=True)
class Decoded:
    """One decoding and the measures its confidence comes from."""

    text: str
    avg_logprob: float
    no_speech_prob: float
    language: str  # the most probable language
    language_prob: float  # its probability
    expected: str  # the language the recogniser listens for
    seconds: float  # of speech

    @property
    def foreign(self) -> float:
        """How sure Whisper is that this is another language (0 on short speech)."""
        other = self.language != self.expected and self.seconds >= LID_MIN_S
        return self.language_prob if other else 0.0

    def confidence(self) -> float:
        if _compression(self.text) > COMPRESSION_LIMIT:
            return 0.0
        scores = (
            1.0 - self.avg_logprob / (2.0 * LOGPROB_LIMIT),
            1.0 - self.no_speech_prob / (2.0 * NO_SPEECH_LIMIT),
            1.0 - self.foreign / (2.0 * FOREIGN_LIMIT),
        )
        return float(np.clip(min(scores), 0.0, 1.0))


def _loops(text: str) -> bool:
    """The same sentence twice in a row: the decoder repeating itself."""
    sentences = [s.strip(" ,").lower() for s in re.split(r"[.?!]", text) if s.strip(" ,")]
    return any(a == b for a, b in pairwise(sentences))


def _compression(text: str) -> float:
    data = text.encode()
    return len(data) / len(gzip.compress(data)) if len(data) > 40 else 1.0


class WhisperRecognizer:
    def __init__(
        self,
        model: Any,
        lang: str,
        prompt: str = "",
        beam_size: int = 1,
    ) -> None:
        if lang not in LANGUAGES:
            raise ConfigError(f"asr whisper: language '{lang}' ({', '.join(LANGUAGES)})")
        self.model = model
        self.lang = lang
        self.beam_size = beam_size
        self.tokenizer = Tokenizer(model.hf_tokenizer, True, task="transcribe", language=lang)
        self.prompt_text = prompt
        prompt_tokens = self.tokenizer.encode(" " + prompt.strip()) if prompt.strip() else []
        self.prompt = model.get_prompt(self.tokenizer, prompt_tokens, without_timestamps=True)
        self.suppress = list(get_suppressed_tokens(self.tokenizer, [-1]))

    def transcribe(self, audio: Audio) -> Transcript:
        decoded = self.decode(audio)
        if decoded is None:
            return Transcript("", 0.0)
        return Transcript(decoded.text, decoded.confidence())

    def decode(self, audio: Audio) -> Decoded | None:
        """The decoding of the speech in ``audio``; None when the VAD hears no speech."""
        span = speech_span(audio)
        if span is None:
            return None
        x = as_float(audio)[span[0] : span[1]]
        seconds = len(x) / 16000
        if seconds > WINDOW_S:
            return self._long(x)
        budget = int(TOKENS_PER_S * seconds) + 8
        short = min(WINDOW_S, max(SHORT_WINDOW_S, seconds + TAIL_S))
        if short < WINDOW_S:
            decoded, tokens = self._window(x, short, budget)
            if tokens < budget and not _loops(decoded.text):
                return decoded
        return self._window(x, WINDOW_S, budget)[0]

    def _encode(self, x: npt.NDArray[np.float32], window_s: float = WINDOW_S) -> Any:
        features = self.model.feature_extractor(x)
        return self.model.encode(pad_or_trim(features, int(window_s * FRAMES_PER_S)))

    def _language(self, encoded: Any) -> tuple[str, float]:
        """The most probable language and its probability."""
        token, prob = self.model.model.detect_language(encoded)[0][0]
        return str(token[2:-2]), float(prob)

    def _window(
        self, x: npt.NDArray[np.float32], window_s: float, budget: int
    ) -> tuple[Decoded, int]:
        """The decoding from a window of ``window_s`` and how many tokens it took."""
        encoded = self._encode(x, window_s)
        top, prob = self._language(encoded)
        result = self.model.model.generate(
            encoded,
            [self.prompt],
            beam_size=self.beam_size,
            max_length=len(self.prompt) + budget,
            return_scores=True,
            return_no_speech_prob=True,
            suppress_blank=True,
            suppress_tokens=self.suppress,
        )[0]
        tokens = result.sequences_ids[0]
        avg_logprob = result.scores[0] * len(tokens) / (len(tokens) + 1)  # length penalty 1
        text = self.tokenizer.decode(tokens).strip()
        no_speech = float(result.no_speech_prob)
        seconds = len(x) / 16000
        return Decoded(text, avg_logprob, no_speech, top, prob, self.lang, seconds), len(tokens)

    def _long(self, x: npt.NDArray[np.float32]) -> Decoded:
        """Past one window (read passages in evaluations): faster-whisper's own segmentation,
        the language judged on the first window."""
        top, prob = self._language(self._encode(x[: int(WINDOW_S * 16000)]))
        seconds = len(x) / 16000
        segments, _ = self.model.transcribe(
            x,
            language=self.lang,
            beam_size=self.beam_size,
            initial_prompt=self.prompt_text or None,
            condition_on_previous_text=False,
            without_timestamps=True,
        )
        segments = list(segments)
        if not segments:
            return Decoded("", -math.inf, 1.0, top, prob, self.lang, seconds)
        weights = [max(len(s.tokens), 1) for s in segments]
        return Decoded(
            " ".join(s.text.strip() for s in segments),
            float(np.average([s.avg_logprob for s in segments], weights=weights)),
            float(np.average([s.no_speech_prob for s in segments], weights=weights)),
            top,
            prob,
            self.lang,
            seconds,
        )


def whisper_model(cfg: AsrConfig) -> Any:
    path = check_model_dir(Path(cfg.whisper_model)) if cfg.whisper_model else packaged_model()
    return load_whisper(path, cfg.whisper_threads, cfg.whisper_compute_type)


def whisper_recognizer(cfg: AsrConfig, grammar: str, lang: str) -> WhisperRecognizer:
    """``grammar``: ``answers`` (Listen), ``none`` (no prompt), else commands."""
    model = whisper_model(cfg)
    prompt = prompt_for(grammar, lang, cfg.vocabulary)
    return WhisperRecognizer(model, lang, prompt, cfg.whisper_beam_size)
