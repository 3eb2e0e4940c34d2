"""JSGF grammars for pocketsphinx, generated from the NLU training data: every example, with
each annotated entity replaced by a rule listing all surface forms of that entity, so the
recogniser accepts exactly what the NLU was taught (and "display my pulse" as well as
"display my blood pressure")."""

from __future__ import annotations

from collections.abc import Callable, Iterable

from amiro.dialogue.text import normalize
from amiro.dialogue.training_data import TrainingData

ANSWER_INTENTS = ("affirm", "deny", "postpone")


def _rule_name(key: str) -> str:
    return key.replace("_", "")


def jsgf(
    data: TrainingData,
    known: Callable[[str], bool],
    intents: Iterable[str] | None = None,
    name: str = "amiro",
) -> str:
    """The grammar of ``data``'s examples (of ``intents``, default all) whose words are all in
    the recogniser's dictionary (``known(word)``)."""
    wanted = set(intents) if intents is not None else None
    surfaces: dict[str, set[str]] = {}
    for surface, pairs in data.gazetteer().items():
        if surface and all(known(w) for w in surface.split()):
            for key, _ in pairs:
                surfaces.setdefault(key, set()).add(surface)
    sentences: set[str] = set()
    for ex in data.examples:
        if wanted is not None and ex.intent not in wanted:
            continue
        text = ex.text
        for surface, key, _ in ex.entities:
            if key in surfaces:
                text = text.replace(surface, f" RULE{_rule_name(key)} ", 1)
        words = normalize(text).split()
        words = [f"<{w[4:]}>" if w.startswith("rule") else w for w in words]
        if words and all(w.startswith("<") or known(w) for w in words):
            sentences.add(" ".join(words))
    used = {w[1:-1] for s in sentences for w in s.split() if w.startswith("<")}
    lines = ["#JSGF V1.0;", f"grammar {name};"]
    for key in sorted(surfaces):
        if _rule_name(key) in used:
            lines.append(f"<{_rule_name(key)}> = {' | '.join(sorted(surfaces[key]))};")
    lines.append(f"public <utterance> = {' | '.join(sorted(sentences))};")
    return "\n".join(lines) + "\n"
