"""What Whisper is told to expect: its initial prompt, built per language from the NLU
training data (one example command per intent, the rooms) and the household's names, so that
"Maria", "hallway" or "tension artérielle" are spelt the way the NLU knows them.  For Listen
(the ``answers`` grammar) the prompt is the language's yes / no / later answers."""

from __future__ import annotations

from collections.abc import Iterable

from amiro.dialogue.grammar import ANSWER_INTENTS
from amiro.dialogue.schema import OUT_OF_SCOPE
from amiro.dialogue.training_data import TrainingData, shipped_training_data

ROOM_KEY = "room_entity"
ANSWERS_PER_INTENT = 4
MAX_CHARS = 600  # well inside Whisper's 223 prompt tokens


def _first(items: Iterable[str], n: int) -> list[str]:
    return list(dict.fromkeys(items))[:n]


def command_prompt(data: TrainingData, names: Iterable[str] = ()) -> str:
    """Names, rooms, then one example per intent, as sentences Whisper continues from."""
    rooms = _first((s for ex in data.examples for s, k, _ in ex.entities if k == ROOM_KEY), 8)
    intents = [i for i in data.intents if i != OUT_OF_SCOPE and i not in ANSWER_INTENTS]
    examples = [next(ex.text for ex in data.examples if ex.intent == i) for i in intents]
    parts = [", ".join([*_first(names, 8), *rooms]), *examples]
    return _clip(". ".join(p[:1].upper() + p[1:] for p in parts if p) + ".")


def answers_prompt(data: TrainingData) -> str:
    """The language's ways of saying yes, no and later."""
    texts = [
        text
        for intent in ANSWER_INTENTS
        for text in _first((ex.text for ex in data.examples if ex.intent == intent), 4)
    ]
    return _clip(". ".join(t[:1].upper() + t[1:] for t in texts) + ".")


def _clip(text: str) -> str:
    return text if len(text) <= MAX_CHARS else text[: text.rfind(". ", 0, MAX_CHARS) + 1]


def prompt_for(grammar: str, lang: str, names: Iterable[str] = ()) -> str:
    """The prompt for a pocketsphinx-style ``grammar`` name: ``answers`` for Listen, ``none``
    for free transcription, anything else for commands."""
    if grammar == "none":
        return ""
    data = shipped_training_data(lang)
    return answers_prompt(data) if grammar == "answers" else command_prompt(data, names)
