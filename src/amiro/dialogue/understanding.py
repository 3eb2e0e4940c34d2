"""The household's NLU: one trained model per language, chosen per utterance from the
speaker's profile or the language the utterance was heard in.  Implements the Listen port."""

from __future__ import annotations

import hashlib
import logging
import os
import pickle
import threading
from dataclasses import replace
from datetime import date
from functools import cache
from pathlib import Path

from amiro import __version__
from amiro.core.cache import cache_dir
from amiro.core.clock import Clock, SimClock
from amiro.core.config import ConfigError
from amiro.core.messages import SpeechHeard
from amiro.dialogue.entities import Entity
from amiro.dialogue.massive import ENV_DIR, massive_partition, read_massive
from amiro.dialogue.nlu import DEFAULT_THRESHOLD, LanguageNlu, Parse, dated
from amiro.dialogue.phrases import check_language
from amiro.dialogue.profiles import SpeakerProfile, language_of
from amiro.dialogue.training_data import load_training_data, shipped_training_data
from amiro.home.household import LANGUAGES

log = logging.getLogger(__name__)
# Part of the cache key: raised whenever what a pickled model holds changes shape (2: the
# entity extractor knows its language), so that an older cached file is never loaded.
MODEL_FORMAT = 2


@cache
def real_examples(lang: str) -> tuple[tuple[str, str], ...]:
    """MASSIVE's train partition in amiro's labels when it is found (``massive_dir``): real
    phrasing of weather, calendar, lights and greetings, and real out-of-scope requests."""
    path = massive_partition(lang, "train")
    if path is None:
        _warn_once(f"MASSIVE not found (set {ENV_DIR}): NLU trained on amiro's data only")
        return ()
    return tuple((r.text, r.intent) for r in read_massive(path))


@cache
def _warn_once(message: str) -> None:
    """One warning a process, however many languages train."""
    log.warning("%s", message)


# One lock per language: a model is trained once even when a warm-up thread and a parse ask
# for it together, and a trained language never waits for another one's training.
_TRAINING: dict[str, threading.Lock] = {lang: threading.Lock() for lang in LANGUAGES}


def shipped_model(lang: str, threshold: float = DEFAULT_THRESHOLD) -> LanguageNlu:
    """Trained once per process: the shipped data never changes at run time."""
    with _TRAINING[check_language(lang)]:
        return _shipped_model(lang, threshold)


@cache
def _shipped_model(lang: str, threshold: float) -> LanguageNlu:
    """Trained from the shipped data and MASSIVE, or loaded from the user's cache when the
    same data trained it before (training with real data takes seconds a language)."""
    data, real = shipped_training_data(lang), real_examples(lang)
    key = hashlib.sha256(
        repr((MODEL_FORMAT, __version__, sklearn_version(), threshold, data, real)).encode()
    ).hexdigest()[:16]
    path = cache_dir() / f"nlu-{lang}-{key}.pickle"
    try:
        model: LanguageNlu = pickle.loads(path.read_bytes())  # our own file, keyed by its data
        return model
    except (OSError, pickle.UnpicklingError, EOFError, AttributeError):
        pass
    model = LanguageNlu(data, threshold, real)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        partial = path.with_suffix(f".{os.getpid()}.tmp")
        partial.write_bytes(pickle.dumps(model))
        partial.replace(path)  # atomic: a concurrent reader sees the whole file or none
    except OSError as exc:
        log.info("NLU model not cached (%s): it trains again next time", exc)
    return model


def sklearn_version() -> str:
    from sklearn import __version__ as version

    return str(version)


class Nlu:
    """``clock``: the runtime's, on which relative days are dated ("in three days" is three
    days after its today); a simulated clock at its epoch when none is given."""

    def __init__(
        self,
        threshold: float = DEFAULT_THRESHOLD,
        training_data: dict[str, Path] | None = None,
        profiles: dict[str, SpeakerProfile] | None = None,
        clock: Clock | None = None,
    ) -> None:
        self.threshold = threshold
        self.training_data = dict(training_data or {})
        self.profiles = dict(profiles or {})
        self.clock: Clock = clock or SimClock()
        self._custom: dict[str, LanguageNlu] = {}

    def today(self) -> date:
        """The clock's date (UTC, as the health store's days)."""
        return date.fromisoformat(self.clock.iso(self.clock.now())[:10])

    def model(self, lang: str) -> LanguageNlu:
        check_language(lang)
        path = self.training_data.get(lang)
        if path is None:
            return shipped_model(lang, self.threshold)
        with _TRAINING[lang]:
            if lang not in self._custom:
                data = load_training_data(path)
                self._custom[lang] = LanguageNlu(data, self.threshold, real_examples(lang))
            return self._custom[lang]

    def warm_up(self) -> threading.Thread:
        """Train the household's languages in the background (English when no one is
        known): training takes seconds with real data, and the first reply must not wait for
        it.  Other languages train when first heard, so a process that serves one language
        (a deployment's edge) does not spend its first seconds on the others."""
        spoken = [p.lang for p in self.profiles.values() if p.lang in LANGUAGES]
        order = list(dict.fromkeys(spoken or ["en"]))
        thread = threading.Thread(target=self._train, args=(order,), name="nlu", daemon=True)
        thread.start()
        return thread

    def _train(self, order: list[str]) -> None:
        for lang in order:
            try:
                self.model(lang)
            except ConfigError:  # bad training data: reported where the model is first used
                return

    def parse(self, text: str, lang: str) -> Parse:
        return self.model(lang).parse(text, self.today())

    def entities(self, text: str, lang: str, keys: tuple[str, ...]) -> list[Entity]:
        """Entities of the given keys whatever the intent: answers to "in which room?"."""
        found = self.model(lang).extractor.extract(text, keys)
        today = self.today()
        return [replace(e, value=dated({e.key: e.value}, today)[e.key]) for e in found]

    def intent(self, heard: SpeechHeard) -> tuple[str, float]:
        lang = heard.lang if heard.lang in LANGUAGES else None
        parsed = self.parse(heard.text, lang or language_of(self.profiles, heard.speaker, "en"))
        return parsed.intent, parsed.confidence * heard.confidence
