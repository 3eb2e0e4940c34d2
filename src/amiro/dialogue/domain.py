"""The dialogue domain (data/dialogue/domain.yaml): rules from intent to action, the slots
each action needs and how to ask for a missing one."""

from __future__ import annotations

from functools import cache
from importlib import resources
from pathlib import Path

from pydantic import Field

from amiro.core.config import Section, parse, read_yaml


class Rule(Section):
    intent: str
    action: str
    required: tuple[str, ...] = ()
    any_of: tuple[str, ...] = ()
    defaults: dict[str, str] = Field(default_factory=dict)

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


def load_domain(path: Path) -> Domain:
    return parse(Domain, read_yaml(path), str(path))


@cache
def shipped_domain() -> Domain:
    return load_domain(Path(str(resources.files("amiro").joinpath("data/dialogue/domain.yaml"))))
