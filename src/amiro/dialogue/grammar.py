"""JSGF grammars for pocketsphinx, generated from the NLU training data.

Each intent becomes a rule listing its training sentences, with every annotated entity
replaced by a rule of all surface forms of that entity (so "display my pulse" is accepted as
well as "display my blood pressure").  The grammar hints (``data/dialogue/grammar/en.yaml``)
generalise beyond the training sentences in a controlled way: optional words around any
command ("could you ... please") and optional prepositions before entities ("for
tomorrow").  Words keep their apostrophes because the dictionary knows how "what's" is
pronounced, not a lone "s" (which it reads as the letter).
"""

from __future__ import annotations

from collections.abc import Callable, Container, Iterable
from dataclasses import dataclass, field
from functools import cache
from importlib import resources
from pathlib import Path

import yaml

from amiro.core.config import ConfigError
from amiro.dialogue.text import normalize
from amiro.dialogue.training_data import Example, TrainingData

ANSWER_INTENTS = ("affirm", "deny", "postpone")


@dataclass(frozen=True)
class GrammarHints:
    lead: tuple[str, ...] = ()
    tail: tuple[str, ...] = ()
    before: dict[str, tuple[str, ...]] = field(default_factory=dict)  # entity key -> words
    pronunciations: dict[str, str] = field(default_factory=dict)  # word -> CMU phones


def spoken_words(text: str) -> list[str]:
    """Lower case words without diacritics or punctuation, keeping apostrophes inside words
    (``"What's up?"`` → ``["what's", "up"]``)."""
    words: list[str] = []
    for token in text.replace("’", "'").split():
        pieces = [normalize(p) for p in token.split("'")]
        words += "'".join(p for p in pieces if p).split()
    return words


def _rule_name(key: str) -> str:
    return key.replace("_", "")


def _alternatives(items: Iterable[str]) -> str:
    return " | ".join(sorted(set(items)))


def _sentence(ex: Example, keys: Container[str], before: dict[str, tuple[str, ...]]) -> list[str]:
    """The example's words, each annotated entity (of ``keys``) replaced by ``<rule>`` and
    without the preposition that the entity's rule already makes optional."""
    marked, cursor = "", 0
    for surface, key, _ in ex.entities:
        at = ex.text.find(surface, cursor)
        if key in keys and at >= 0:
            marked += f"{ex.text[cursor:at]} <{_rule_name(key)}> "
            cursor = at + len(surface)
    words: list[str] = []
    for token in (marked + ex.text[cursor:]).split():
        if not token.startswith("<"):
            words += spoken_words(token)
            continue
        if words and words[-1] in before.get(token[1:-1], ()):
            words.pop()
        words.append(token)
    return words


def _entity_surfaces(
    data: TrainingData, speakable: Callable[[Iterable[str]], bool]
) -> dict[str, set[str]]:
    """Entity key → its speakable surface forms, in their spoken form where an example has
    one (the gazetteer's are normalised: "what s your name")."""
    spoken = {
        normalize(s): " ".join(spoken_words(s)) for e in data.examples for s, *_ in e.entities
    }
    surfaces: dict[str, set[str]] = {}
    for surface, pairs in data.gazetteer().items():
        words = spoken.get(surface, surface)
        if words and speakable(words.split()):
            for key, _ in pairs:
                surfaces.setdefault(key, set()).add(words)
    return surfaces


def jsgf(
    data: TrainingData,
    known: Callable[[str], bool],
    intents: Iterable[str] | None = None,
    hints: GrammarHints | None = None,
    chain: bool = False,
    name: str = "amiro",
) -> str:
    """The grammar of ``data``'s examples (of ``intents``, default all) whose words are all
    in the recogniser's dictionary (``known(word)``) or in the hints' pronunciations.  With
    ``chain``, two sentences of the same intent may follow each other ("no, I'm not
    thirsty": replies to the robot's questions often do), without lead words (mostly
    answers themselves: "okay")."""
    hints = hints or GrammarHints()

    def speakable(words: Iterable[str]) -> bool:
        return all(w in hints.pronunciations or known(w) for w in words)

    surfaces = _entity_surfaces(data, speakable)
    wanted = set(intents) if intents is not None else None
    before = {_rule_name(k): v for k, v in hints.before.items()}
    sentences: dict[str, set[str]] = {}
    for ex in data.examples:
        words = _sentence(ex, surfaces, before)
        if (
            (wanted is None or ex.intent in wanted)
            and words
            and speakable(w for w in words if not w.startswith("<"))
        ):
            sentences.setdefault(_rule_name(f"intent_{ex.intent}"), set()).add(" ".join(words))
    used = " ".join(s for group in sentences.values() for s in group)
    rules: dict[str, str] = {}
    for key in sorted(surfaces):
        if f"<{_rule_name(key)}>" in used:
            optional = [w for w in hints.before.get(key, ()) if speakable([w])]
            prefix = f"[{_alternatives(optional)}] " if optional else ""
            rules[_rule_name(key)] = f"{prefix}({_alternatives(surfaces[key])})"
    rules.update({rule: _alternatives(group) for rule, group in sentences.items()})
    for side, phrases in (("lead", hints.lead), ("tail", hints.tail)):
        if said := [p for p in phrases if speakable(p.split())]:
            rules[side] = _alternatives(said)
    if chain:
        rules.pop("lead", None)
    repeat = " [<{}>]" if chain else ""
    body = "(" + " | ".join(f"<{r}>{repeat.format(r)}" for r in sorted(sentences)) + ")"
    lead = "[<lead>] " if "lead" in rules else ""
    tail = " [<tail>]" if "tail" in rules else ""
    lines = ["#JSGF V1.0;", f"grammar {name};"]
    lines += [f"<{rule}> = {alternatives};" for rule, alternatives in rules.items()]
    lines.append(f"public <utterance> = {lead}{body}{tail};")
    return "\n".join(lines) + "\n"


def _strings(value: object, source: str, what: str) -> tuple[str, ...]:
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise ConfigError(f"{source}: '{what}' must be a list of strings")
    return tuple(" ".join(spoken_words(v)) for v in value)


def load_hints(path: Path) -> GrammarHints:
    if not path.is_file():
        raise ConfigError(f"{path}: no such file")
    try:
        data = yaml.safe_load(path.read_text(encoding="utf-8")) or {}
    except yaml.YAMLError as exc:
        raise ConfigError(f"{path}: invalid YAML: {str(exc).splitlines()[0]}") from None
    if not isinstance(data, dict):
        raise ConfigError(f"{path}: expected a mapping")
    before = data.get("before") or {}
    prons = data.get("pronunciations") or {}
    if not isinstance(before, dict) or not isinstance(prons, dict):
        raise ConfigError(f"{path}: 'before' and 'pronunciations' must be mappings")
    return GrammarHints(
        lead=_strings(data.get("lead") or [], str(path), "lead"),
        tail=_strings(data.get("tail") or [], str(path), "tail"),
        before={str(k): _strings(v, str(path), f"before.{k}") for k, v in before.items()},
        pronunciations={str(k).lower(): str(v) for k, v in prons.items()},
    )


@cache
def shipped_hints(lang: str) -> GrammarHints:
    """The grammar hints amiro ships for ``lang`` (English only: the bundled model's)."""
    path = Path(str(resources.files("amiro").joinpath(f"data/dialogue/grammar/{lang}.yaml")))
    return load_hints(path)
