"""Per-language phrase templates: answers come in the listener's language."""

from __future__ import annotations

from collections.abc import Mapping
from functools import cache
from importlib import resources
from typing import Any

import yaml

from amiro.core.config import ConfigError
from amiro.dialogue.text import normalize
from amiro.home.household import LANGUAGES


@cache
def _table() -> dict[str, dict[str, str]]:
    text = resources.files("amiro").joinpath("data/dialogue/phrases.yaml").read_text("utf-8")
    data: dict[str, dict[str, str]] = yaml.safe_load(text)
    return data


def check_language(lang: str) -> str:
    if lang not in LANGUAGES:
        raise ConfigError(f"unknown language '{lang}' (choices: {', '.join(LANGUAGES)})")
    return lang


def local_name(kind: str, value: str, lang: str) -> str:
    """A room, device state or place in ``lang`` (``room``, ``kitchen`` → "bucătărie");
    a value without an entry (a person, an unknown town) is said as given."""
    key = f"{kind}_{'_'.join(normalize(value).split())}"
    return phrase(key, lang) if key in _table() else value


Responses = Mapping[str, Mapping[str, str]]  # key -> language -> template


def has_phrase(key: str, own: Responses | None = None) -> bool:
    return key in (own or {}) or key in _table()


def phrase(
    key: str, lang: str, fields: Mapping[str, Any] | None = None, own: Responses | None = None
) -> str:
    """The phrase ``key`` in ``lang`` with ``{fields}`` filled in; ``own``: a user's
    responses (their domain's), tried before amiro's."""
    entry = (own or {}).get(key) or _table().get(key)
    if entry is None:
        raise KeyError(f"no phrase named '{key}'")
    template = entry.get(check_language(lang)) or entry["en"]
    return template.format_map(dict(fields or {}))
