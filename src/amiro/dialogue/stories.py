"""Story-driven next action (Rasa's MemoizationPolicy): the last turns of a conversation,
intents and actions, are looked up among the prefixes of the stories (data/dialogue/dm/
stories.yml), so that a follow-up ("and yesterday?") repeats the last action with its slots."""

from __future__ import annotations

from collections.abc import Sequence
from functools import cache
from importlib import resources
from pathlib import Path

from pydantic import model_validator

from amiro.core.config import Section, parse, read_yaml
from amiro.dialogue.text import normalize

INFORM = "inform"  # a follow-up turn: its meaning comes from the story, not the classifier
MAX_HISTORY = 3  # events (intents and actions) a story prefix is matched on


class Step(Section):
    intent: str = ""
    action: str = ""
    entities: tuple[str, ...] = ()  # for an intent: the slots this turn may change

    @model_validator(mode="after")
    def _one_of(self) -> Step:
        if bool(self.intent) == bool(self.action):
            raise ValueError("a step has either an intent or an action")
        return self

    @property
    def event(self) -> str:
        return f"intent:{self.intent}" if self.intent else f"action:{self.action}"


class Story(Section):
    story: str
    steps: tuple[Step, ...]


class Stories(Section):
    followup: dict[str, tuple[str, ...]]
    stories: tuple[Story, ...]

    def is_followup(self, text: str, lang: str) -> bool:
        words = normalize(text).split()
        return any(words[: len(m.split())] == m.split() for m in self.followup.get(lang, ()))


class Memoization:
    """Story prefix (the last ``MAX_HISTORY`` events or fewer) → the next action and the
    slots its user turn may change."""

    def __init__(self, stories: Stories) -> None:
        self._next: dict[tuple[str, ...], tuple[str, tuple[str, ...]]] = {}
        for story in stories.stories:
            events = [s.event for s in story.steps]
            for i, step in enumerate(story.steps):
                if step.action and i > 0 and story.steps[i - 1].intent:
                    key = tuple(events[max(0, i - MAX_HISTORY) : i])
                    self._next[key] = (step.action, story.steps[i - 1].entities)

    def predict(self, events: Sequence[str]) -> tuple[str, tuple[str, ...]] | None:
        """The longest remembered prefix wins; a lone intent is the rules' job."""
        for n in range(min(MAX_HISTORY, len(events)), 1, -1):
            found = self._next.get(tuple(events[-n:]))
            if found is not None:
                return found
        return None


def load_stories(path: Path) -> Stories:
    return parse(Stories, read_yaml(path), str(path))


@cache
def shipped_stories() -> Stories:
    where = resources.files("amiro").joinpath("data/dialogue/dm/stories.yml")
    return load_stories(Path(str(where)))
