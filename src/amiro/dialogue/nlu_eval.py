"""``amiro nlu evaluate``: intent and entity accuracy, the confusion matrix in the shape of
the paper's Tables 4–6, and the time per utterance, per language."""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

from amiro.core.config import ConfigError
from amiro.dialogue.nlu import Parse
from amiro.dialogue.phrases import check_language
from amiro.dialogue.schema import OUT_OF_SCOPE
from amiro.dialogue.text import normalize

NAME_KEYS = ("person_entity", "location_entity")  # compared case- and diacritic-insensitively


@dataclass(frozen=True)
class Labelled:
    lang: str
    text: str
    intent: str
    entities: dict[str, str]


def read_records(
    path: Path, parse: Callable[[dict[str, Any]], Labelled | None], what: str
) -> list[Labelled]:
    """The rows ``parse`` makes of a JSON-lines file's records (None: a record it skips);
    blank lines are skipped, a record it cannot read is a one-line error naming its line."""
    if not path.is_file():
        raise ConfigError(f"{path}: no such file")
    rows: list[Labelled] = []
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        if not line.strip():
            continue
        try:
            row = parse(json.loads(line))
        except (json.JSONDecodeError, KeyError, TypeError, AttributeError) as exc:
            raise ConfigError(f"{path}:{number}: not {what} ({exc})") from None
        if row is not None:
            rows.append(row)
    return rows


def _labelled(obj: dict[str, Any]) -> Labelled:
    return Labelled(
        check_language(str(obj["lang"])),
        str(obj["text"]),
        str(obj["intent"]),
        {str(k): str(v) for k, v in (obj.get("entities") or {}).items()},
    )


def read_jsonl(path: Path) -> list[Labelled]:
    rows = read_records(path, _labelled, "a labelled utterance")
    if not rows:
        raise ConfigError(f"{path}: no utterances")
    return rows


def shipped_eval_files() -> list[Path]:
    """amiro's own held-out files, one per language (written apart from the training data)."""
    folder = resources.files("amiro").joinpath("data/dialogue/eval")
    return [Path(str(folder.joinpath(f"{lang}.jsonl"))) for lang in ("en", "ro", "fr")]


def same_value(key: str, expected: str, got: str | None) -> bool:
    if got is None:
        return False
    if key in NAME_KEYS:
        return normalize(expected) == normalize(got)
    return expected == got


def _share(right: int, n: int) -> float | None:
    return right / n if n else None


def evaluate(
    rows: list[Labelled],
    parse: Callable[[str, str], Parse],
    progress: Callable[[str, int, int], None] | None = None,
) -> dict[str, Any]:
    """Per language: ``{n, intent_accuracy, entity_accuracy, in_scope_accuracy,
    out_of_scope_rejection, confusion, ms_per_utterance}`` (a share is None without rows of
    its kind).  ``progress(lang, done, total)`` is called every 500 utterances."""
    out: dict[str, Any] = {}
    for lang in sorted({r.lang for r in rows}):
        subset = [r for r in rows if r.lang == lang]
        parse(lang, subset[0].text)  # trains the model outside the timing
        confusion: dict[str, dict[str, int]] = {}
        right = pairs = pairs_right = 0
        scope = {True: [0, 0], False: [0, 0]}  # in scope? -> [right, n]
        errors: list[dict[str, Any]] = []
        results: list[Parse] = []
        elapsed = 0.0
        for done, r in enumerate(subset, 1):
            start = time.perf_counter()
            results.append(parse(lang, r.text))
            elapsed += time.perf_counter() - start
            if progress is not None and (done % 500 == 0 or done == len(subset)):
                progress(lang, done, len(subset))
        for r, p in zip(subset, results, strict=True):
            row = confusion.setdefault(r.intent, {})
            row[p.intent] = row.get(p.intent, 0) + 1
            right += p.intent == r.intent
            counts = scope[r.intent != OUT_OF_SCOPE]
            counts[0] += p.intent == r.intent
            counts[1] += 1
            ok = [same_value(k, v, p.entities.get(k)) for k, v in r.entities.items()]
            pairs += len(ok)
            pairs_right += sum(ok)
            if p.intent != r.intent or not all(ok):
                errors.append({"text": r.text, "intent": p.intent, "entities": p.entities})
        out[lang] = {
            "n": len(subset),
            "intent_accuracy": right / len(subset),
            "entity_accuracy": pairs_right / pairs if pairs else 1.0,
            "in_scope_accuracy": _share(*scope[True]),
            "out_of_scope_rejection": _share(*scope[False]),
            "confusion": confusion,
            "ms_per_utterance": 1000.0 * elapsed / len(subset),
            "errors": errors,
        }
    return out
