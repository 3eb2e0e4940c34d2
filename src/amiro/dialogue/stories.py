"""Story-driven next action (Rasa's MemoizationPolicy): the last turns of a conversation,
intents and actions, are looked up among the prefixes of the stories (data/dialogue/dm/
stories.yml, shared by the languages, plus ``stories.<lang>.yml``: the words that open a
follow-up in that language and any story of its own), so that a follow-up ("and
yesterday?") repeats the last action with its slots."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cache
from importlib import resources
from pathlib import Path

from pydantic import Field, model_validator

from amiro.core.config import ConfigError, Section, parse, read_yaml
from amiro.dialogue.text import normalize
from amiro.home.household import LANGUAGES

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


class StoryFile(Section):
    """A stories file: the words that open a follow-up, per language, and the stories."""

    followup: dict[str, tuple[str, ...]] = Field(default_factory=dict)
    stories: tuple[Story, ...] = ()


@dataclass(frozen=True)
class Stories:
    """The shared stories, and per language its follow-up words and stories of its own."""

    followup: dict[str, tuple[str, ...]]
    stories: tuple[Story, ...]
    by_lang: dict[str, tuple[Story, ...]] = field(default_factory=dict)

    def is_followup(self, text: str, lang: str) -> bool:
        words = normalize(text).split()
        return any(words[: len(m.split())] == m.split() for m in self.followup.get(lang, ()))

    def of(self, lang: str) -> tuple[Story, ...]:
        """The shared stories and ``lang``'s own."""
        return self.stories + self.by_lang.get(lang, ())


class Memoization:
    """Story prefix (the last ``MAX_HISTORY`` events or fewer) → the next action and the
    slots its user turn may change."""

    def __init__(self, stories: Sequence[Story]) -> None:
        self._next: dict[tuple[str, ...], tuple[str, tuple[str, ...]]] = {}
        for story in stories:
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


def load_stories(path: Path) -> StoryFile:
    return parse(StoryFile, read_yaml(path), str(path))


def load_story_files(folder: Path | None, languages: Sequence[str]) -> Stories:
    """``stories.yml`` and each language's ``stories.<lang>.yml`` (whose ``followup`` must be
    that language's), from ``folder`` where it has them (:func:`dm_file`)."""
    shared = load_stories(dm_file("stories.yml", folder))
    followup, by_lang = dict(shared.followup), {}
    for lang in languages:
        path = dm_file(f"stories.{lang}.yml", folder)
        own = load_stories(path)
        if set(own.followup) - {lang}:
            raise ConfigError(f"{path}: followup: only '{lang}' words belong in this file")
        followup[lang] = followup.get(lang, ()) + own.followup.get(lang, ())
        by_lang[lang] = own.stories
    return Stories(followup, shared.stories, by_lang)


def shipped_dm_dir() -> Path:
    return Path(str(resources.files("amiro").joinpath("data/dialogue/dm")))


def dm_file(name: str, folder: Path | None = None) -> Path:
    """The user's ``folder/name`` when it has that file, else the shipped one: a user's
    folder replaces the files it holds and keeps amiro's others."""
    if folder is not None and (folder / name).is_file():
        return folder / name
    return shipped_dm_dir() / name


@cache
def shipped_stories() -> Stories:
    return load_story_files(None, LANGUAGES)
