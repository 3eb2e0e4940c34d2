"""Amazon MASSIVE 1.0 records (CC BY 4.0, FitzGerald et al. 2022) read as amiro's labels, with
the mapping of ``../shared/data/nlu/MAPPING.md``: weather, calendar queries, lights on/off and
greetings are in scope; the scenarios amiro does not serve are real out-of-scope examples;
intents too close to what amiro may grow into are left out (not scored, not trained on)."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

from amiro.core.config import ConfigError
from amiro.dialogue.nlu_eval import Labelled, read_jsonl, read_records
from amiro.dialogue.schema import OUT_OF_SCOPE

LOCALES = {"en": "en-US", "fr": "fr-FR", "ro": "ro-RO"}
IN_SCOPE: dict[str, tuple[str, dict[str, str]]] = {
    "weather_query": ("get_weather", {}),
    "calendar_query": ("get_calendar", {}),
    "iot_hue_lighton": ("control_device", {"device_entity": "lights", "device_state": "on"}),
    "iot_hue_lightoff": ("control_device", {"device_entity": "lights", "device_state": "off"}),
    "general_greet": ("greet", {}),
}
OUT_OF_SCOPE_SCENARIOS = frozenset(
    {"music", "play", "takeaway", "cooking", "transport", "email", "news", "social", "lists"}
    | {"recommendation", "audio"}
)
OUT_OF_SCOPE_INTENTS = frozenset(
    {"qa_currency", "qa_stock", "qa_maths", "qa_definition", "general_joke", "iot_coffee"}
    | {"iot_cleaning", "alarm_set", "alarm_remove", "alarm_query"}
)
ENV_DIR = "AMIRO_MASSIVE_DIR"


def mapped(scenario: str, intent: str) -> tuple[str, dict[str, str]] | None:
    """amiro's intent and entities for a MASSIVE label, or None when it is not scored."""
    if intent in IN_SCOPE:
        return IN_SCOPE[intent]
    if scenario in OUT_OF_SCOPE_SCENARIOS or intent in OUT_OF_SCOPE_INTENTS:
        return OUT_OF_SCOPE, {}
    return None


def is_massive_record(line: str) -> bool:
    """A MASSIVE jsonl line (``locale``, ``utt``, ``intent``) rather than amiro's format."""
    try:
        obj = json.loads(line)
    except json.JSONDecodeError:
        return False
    return isinstance(obj, dict) and {"locale", "utt", "intent"} <= obj.keys()


def read_massive(path: Path) -> list[Labelled]:
    """The scored records of a MASSIVE jsonl file in amiro's labels (unknown locales skipped)."""
    lang_of = {locale: lang for lang, locale in LOCALES.items()}

    def scored(obj: dict[str, Any]) -> Labelled | None:
        lang = lang_of.get(str(obj["locale"]))
        label = mapped(str(obj.get("scenario", "")), str(obj["intent"]))
        if lang is None or label is None:
            return None
        return Labelled(lang, str(obj["utt"]), label[0], dict(label[1]))

    rows = read_records(path, scored, "a MASSIVE record")
    if not rows:
        raise ConfigError(f"{path}: no scored MASSIVE records in en-US, fr-FR or ro-RO")
    return rows


def massive_dir() -> Path | None:
    """Where the MASSIVE partitions are: ``$AMIRO_MASSIVE_DIR``, else ``shared/data/nlu/massive``
    beside the source checkout or one of its parents (``../shared`` in CI); None when absent."""
    env = os.environ.get(ENV_DIR)
    if env:
        return Path(env) if Path(env).is_dir() else None
    here = Path(__file__).resolve().parents
    root = next((p for p in here if (p / "pyproject.toml").is_file()), None)
    for parent in () if root is None else root.parents:
        candidate = parent / "shared" / "data" / "nlu" / "massive"
        if candidate.is_dir():
            return candidate
    return None


def massive_partition(lang: str, partition: str) -> Path | None:
    folder = massive_dir()
    path = None if folder is None else folder / f"{LOCALES[lang]}.{partition}.jsonl"
    return path if path is not None and path.is_file() else None


def read_labelled(path: Path) -> list[Labelled]:
    """amiro's evaluation format or MASSIVE's, told apart by the first record."""
    if not path.is_file():
        raise ConfigError(f"{path}: no such file")
    with path.open(encoding="utf-8") as f:
        first = next((line for line in f if line.strip()), "")
    return read_massive(path) if is_massive_record(first) else read_jsonl(path)
