"""Per-language NLU: a character and word n-gram linear SVM for the intent, the fuzzy
gazetteer for entities, and a confidence threshold for out-of-scope (the paper's
``no_detected``).  Character n-grams over diacritic-free text are what make it robust to
typos, missing Romanian and French diacritics and ASR slips (measured in docs/dialogue.md)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from sklearn.feature_extraction.text import TfidfVectorizer  # type: ignore[import-untyped,import-not-found,unused-ignore]
from sklearn.pipeline import FeatureUnion, Pipeline  # type: ignore[import-untyped,import-not-found,unused-ignore]
from sklearn.svm import LinearSVC  # type: ignore[import-untyped,import-not-found,unused-ignore]

from amiro.dialogue.entities import EntityExtractor
from amiro.dialogue.schema import INTENT_ENTITIES, OUT_OF_SCOPE
from amiro.dialogue.text import normalize
from amiro.dialogue.training_data import TrainingData

DEFAULT_THRESHOLD = 0.3
SOFTMAX_SCALE = 5.0  # turns SVM margins into confidences that spread over [0, 1]


@dataclass(frozen=True)
class Parse:
    text: str
    lang: str
    intent: str
    confidence: float
    entities: dict[str, str] = field(default_factory=dict)
    ranking: tuple[tuple[str, float], ...] = ()


def _classifier() -> Pipeline:
    features = FeatureUnion(
        [
            ("chars", TfidfVectorizer(analyzer="char_wb", ngram_range=(2, 5), sublinear_tf=True)),
            ("words", TfidfVectorizer(analyzer="word", ngram_range=(1, 2), sublinear_tf=True)),
        ]
    )
    return Pipeline([("features", features), ("model", LinearSVC(C=1.0))])


class LanguageNlu:
    """The NLU of one language, trained from its :class:`TrainingData`."""

    def __init__(self, data: TrainingData, threshold: float = DEFAULT_THRESHOLD) -> None:
        self.lang = data.lang
        self.threshold = threshold
        self.classifier = _classifier()
        texts = [normalize(e.text) for e in data.examples]
        self.classifier.fit(texts, [e.intent for e in data.examples])
        self.labels: list[str] = [str(c) for c in self.classifier.classes_]
        self.extractor = EntityExtractor(data.gazetteer())

    def parse(self, text: str) -> Parse:
        clean = normalize(text)
        if not clean:
            return Parse(text, self.lang, OUT_OF_SCOPE, 1.0)
        margins = self.classifier.decision_function([clean])[0] * SOFTMAX_SCALE
        probs = np.exp(margins - margins.max())
        probs /= probs.sum()
        order = np.argsort(probs)[::-1]
        ranking = tuple((self.labels[i], float(probs[i])) for i in order[:3])
        intent, confidence = ranking[0]
        if confidence < self.threshold:
            intent = OUT_OF_SCOPE
        allowed = INTENT_ENTITIES.get(intent, ())
        entities = (
            {e.key: e.value for e in self.extractor.extract(clean, allowed)} if allowed else {}
        )
        return Parse(text, self.lang, intent, confidence, entities, ranking)
