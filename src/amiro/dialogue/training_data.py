"""Rasa-style NLU training data: intents with annotated examples, synonyms and lookup tables.

Annotation: ``[surface](key)`` takes its canonical value from a synonym (or is its own
value); ``[surface](key:value)`` names the value directly.  The gazetteer built here maps
every known surface form, normalised, to its ``(key, value)`` pairs.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from functools import cache
from importlib import resources
from pathlib import Path

import yaml

from amiro.core.config import ConfigError
from amiro.dialogue.text import normalize

_ANNOTATION = re.compile(r"\[([^\]]+)\]\(([a-z_]+)(?::([^)]+))?\)")


@dataclass(frozen=True)
class Example:
    text: str
    intent: str
    entities: tuple[tuple[str, str, str], ...]  # (surface, key, value as annotated or None)


@dataclass
class TrainingData:
    lang: str
    examples: list[Example] = field(default_factory=list)
    synonyms: dict[str, str] = field(default_factory=dict)  # normalised surface -> value
    lookups: dict[str, list[str]] = field(default_factory=dict)

    @property
    def intents(self) -> list[str]:
        return sorted({e.intent for e in self.examples})

    def gazetteer(self) -> dict[str, set[tuple[str, str]]]:
        """Normalised surface form → the (entity key, canonical value) pairs it can mean."""
        keys_of_value: dict[str, set[str]] = {}
        table: dict[str, set[tuple[str, str]]] = {}
        for ex in self.examples:
            for surface, key, value in ex.entities:
                canonical = value or self.synonyms.get(normalize(surface), normalize(surface))
                keys_of_value.setdefault(canonical, set()).add(key)
                table.setdefault(normalize(surface), set()).add((key, canonical))
        for surface, value in self.synonyms.items():
            for key in keys_of_value.get(value, ()):
                table.setdefault(surface, set()).add((key, value))
        for key, names in self.lookups.items():
            for name in names:
                table.setdefault(normalize(name), set()).add((key, name.lower()))
        return table


def _items(block: str) -> list[str]:
    return [line.strip()[2:].strip() for line in block.splitlines() if line.strip()[:2] == "- "]


def parse_example(line: str, intent: str) -> Example:
    entities = tuple((m.group(1), m.group(2), m.group(3) or "") for m in _ANNOTATION.finditer(line))
    return Example(_ANNOTATION.sub(lambda m: m.group(1), line), intent, entities)


def parse_training_data(data: object, source: str) -> TrainingData:
    if not isinstance(data, dict) or not isinstance(data.get("nlu"), list):
        raise ConfigError(f"{source}: expected a mapping with an 'nlu' list")
    out = TrainingData(lang=str(data.get("language", "")))
    for item in data["nlu"]:
        if not isinstance(item, dict) or not isinstance(item.get("examples"), str):
            raise ConfigError(f"{source}: every nlu item needs an 'examples' block")
        lines = _items(item["examples"])
        if "intent" in item:
            out.examples += [parse_example(line, str(item["intent"])) for line in lines]
        elif "synonym" in item:
            out.synonyms.update({normalize(line): str(item["synonym"]) for line in lines})
        elif "lookup" in item:
            out.lookups.setdefault(str(item["lookup"]), []).extend(lines)
        else:
            raise ConfigError(f"{source}: nlu item without intent, synonym or lookup")
    return out


def load_training_data(path: Path) -> TrainingData:
    if not path.is_file():
        raise ConfigError(f"{path}: no such file")
    try:
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
    except yaml.YAMLError as exc:
        raise ConfigError(f"{path}: invalid YAML: {str(exc).splitlines()[0]}") from None
    return parse_training_data(data, str(path))


@cache
def shipped_training_data(lang: str) -> TrainingData:
    """The training data amiro ships for ``lang`` (en, ro, fr)."""
    path = Path(str(resources.files("amiro").joinpath(f"data/dialogue/nlu/{lang}.yaml")))
    return load_training_data(path)
