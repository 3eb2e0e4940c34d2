"""The dialogue domain: the rules from intent to action (data/dialogue/dm/rules.yml, Rasa's
rules.yml format) joined with the slots each action needs and how to ask for a missing one
(data/dialogue/domain.yaml)."""

from __future__ import annotations

from functools import cache
from importlib import resources
from pathlib import Path

from pydantic import Field, model_validator

from amiro.core.config import Section, parse, read_yaml
from amiro.dialogue.stories import Step


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

    def rule(self, intent: str) -> Rule | None:
        return next((r for r in self.rules if r.intent == intent), None)

    def for_action(self, action: str) -> Rule | None:
        """The slots an action needs, for a story that predicts it."""
        return next((r for r in self.rules if r.action == action), None)


class _DomainFile(Section):
    actions: dict[str, Slots] = Field(default_factory=dict)
    ask: dict[str, str] = Field(default_factory=dict)


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
    return Domain(rules=tuple(rules), ask=domain.ask)


def _shipped(name: str) -> Path:
    return Path(str(resources.files("amiro").joinpath(f"data/dialogue/{name}")))


@cache
def shipped_domain() -> Domain:
    return load_domain(_shipped("domain.yaml"), _shipped("dm/rules.yml"))
