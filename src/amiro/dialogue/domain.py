"""The dialogue domain: the rules from intent to action (data/dialogue/dm/rules.yml, Rasa's
rules.yml format) joined with the slots each action needs and how to ask for a missing one
(data/dialogue/dm/domain.yml); :func:`load_dm` reads them and the stories from a user's
folder laid out like data/dialogue/dm (``dialogue.dm`` in the configuration)."""

from __future__ import annotations

from functools import cache
from pathlib import Path

from pydantic import Field, model_validator

from amiro.core.config import ConfigError, Section, parse, read_yaml
from amiro.dialogue.phrases import has_phrase
from amiro.dialogue.stories import Step, Stories, dm_file, load_story_files, shipped_stories
from amiro.home.household import LANGUAGES


class Slots(Section):
    required: tuple[str, ...] = ()
    any_of: tuple[str, ...] = ()
    defaults: dict[str, str] = Field(default_factory=dict)


class Rule(Slots):
    intent: str
    action: str

    def missing(self, slots: dict[str, str]) -> list[str]:
        """Slots still to ask for, in the order they are asked."""
        out = [s for s in self.required if s not in slots]
        if self.any_of and not any(s in slots for s in self.any_of):
            out.append(self.any_of[0])
        return out


class Domain(Section):
    rules: tuple[Rule, ...]
    ask: dict[str, str] = Field(default_factory=dict)
    responses: dict[str, dict[str, str]] = Field(default_factory=dict)  # a user's own

    def rule(self, intent: str) -> Rule | None:
        return next((r for r in self.rules if r.intent == intent), None)

    def for_action(self, action: str) -> Rule | None:
        """The slots an action needs, for a story that predicts it."""
        return next((r for r in self.rules if r.action == action), None)


class _DomainFile(Section):
    actions: dict[str, Slots] = Field(default_factory=dict)
    ask: dict[str, str] = Field(default_factory=dict)
    # A user's own responses, per language (Rasa's domain ``responses``); English is the one
    # said in a language a response lacks.
    responses: dict[str, dict[str, str]] = Field(default_factory=dict)

    @model_validator(mode="after")
    def _english_first(self) -> _DomainFile:
        for key, texts in self.responses.items():
            if set(texts) - set(LANGUAGES):
                raise ValueError(f"{key}: languages are {', '.join(LANGUAGES)}")
        lacking = sorted(k for k, texts in self.responses.items() if "en" not in texts)
        if lacking:
            raise ValueError(
                f"responses without English (said when a language lacks one): {lacking}"
            )
        return self


class _RuleSteps(Section):
    rule: str
    steps: tuple[Step, Step]

    @model_validator(mode="after")
    def _intent_then_action(self) -> _RuleSteps:
        if not (self.steps[0].intent and self.steps[1].action):
            raise ValueError("a rule is one intent step then one action step")
        return self


class _RulesFile(Section):
    rules: tuple[_RuleSteps, ...]


def load_domain(path: Path, rules_path: Path) -> Domain:
    domain = parse(_DomainFile, read_yaml(path), str(path))
    found = parse(_RulesFile, read_yaml(rules_path), str(rules_path))
    rules = []
    for r in found.rules:
        action = r.steps[1].action
        slots = domain.actions.get(action, Slots())
        rules.append(Rule(intent=r.steps[0].intent, action=action, **slots.model_dump()))
    said = [r.action for r in rules if r.action.startswith("utter_")] + list(domain.ask.values())
    unknown = sorted({k for k in said if not has_phrase(k, domain.responses)})
    if unknown:
        raise ConfigError(
            f"{rules_path}: no response named {', '.join(unknown)} (add it to {path})"
        )
    return Domain(rules=tuple(rules), ask=domain.ask, responses=domain.responses)


@cache
def shipped_domain() -> Domain:
    return load_domain(dm_file("domain.yml"), dm_file("rules.yml"))


def load_dm(folder: Path | None) -> tuple[Domain, Stories]:
    """The domain, rules and stories of ``folder`` (``domain.yml``, ``rules.yml``,
    ``stories.yml``, ``stories.<lang>.yml``; amiro's own for the files it lacks), or amiro's
    when None."""
    if folder is None:
        return shipped_domain(), shipped_stories()
    if not folder.is_dir():
        raise ConfigError(f"{folder}: no such directory (dialogue.dm: stories, rules, domain)")
    domain = load_domain(dm_file("domain.yml", folder), dm_file("rules.yml", folder))
    return domain, load_story_files(folder, LANGUAGES)
