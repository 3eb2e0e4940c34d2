"""Dialogue management: rules pick the action for an intent, missing slots are asked for
over several turns, and every answer comes in the user's language with the paper's default
output (display and say unless the user asked for one of them)."""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field

from amiro.dialogue.actions import Actions
from amiro.dialogue.domain import Domain, Rule
from amiro.dialogue.phrases import phrase
from amiro.dialogue.understanding import Nlu

CANCEL_INTENTS = ("deny", "goodbye")


@dataclass(frozen=True)
class Answer:
    text: str
    lang: str
    intent: str
    entities: dict[str, str]
    action: str = ""  # the action run, or "" while asking
    ask: str = ""  # the slot asked for
    display: bool = True
    say: bool = True


@dataclass
class _Pending:
    rule: Rule
    slots: dict[str, str]
    asking: str


@dataclass
class Turn:
    user: str
    text: str
    answer: Answer


@dataclass
class DialogueManager:
    nlu: Nlu
    domain: Domain
    actions: Actions
    history: deque[Turn] = field(default_factory=lambda: deque(maxlen=200))
    _pending: dict[str, _Pending] = field(default_factory=dict)

    def awaiting(self, user: str) -> bool:
        return user in self._pending

    def handle(self, text: str, lang: str, user: str = "") -> Answer:
        parsed = self.nlu.parse(text, lang)
        pending = self._pending.pop(user, None)
        if pending is not None and parsed.intent in CANCEL_INTENTS:
            answer = self._say("utter_cancelled", {}, lang, parsed.intent, parsed.entities)
        elif pending is not None:
            found = self.nlu.entities(text, lang, tuple(pending.rule.missing(pending.slots)))
            pending.slots.update({e.key: e.value for e in found})
            answer = self._advance(pending, lang, user, pending.rule.intent, parsed.entities)
        elif not text.strip():  # nothing heard (speech rejected): not a request it cannot serve
            answer = self._say("utter_not_understood", {}, lang, parsed.intent, {})
        else:
            rule = self.domain.rule(parsed.intent) or self.domain.rule("out_of_scope")
            assert rule is not None, "the domain needs an out_of_scope rule"
            slots = {**rule.defaults, **parsed.entities}
            answer = self._advance(_Pending(rule, slots, ""), lang, user, parsed.intent, slots)
        self.history.append(Turn(user, text, answer))
        return answer

    def _advance(
        self, pending: _Pending, lang: str, user: str, intent: str, entities: dict[str, str]
    ) -> Answer:
        missing = pending.rule.missing(pending.slots)
        if missing:
            pending.asking = missing[0]
            self._pending[user] = pending
            key = self.domain.ask.get(missing[0], "utter_not_understood")
            return Answer(phrase(key, lang), lang, intent, entities, ask=missing[0])
        key, fields = self.actions.run(pending.rule.action, pending.slots, user, lang)
        output = pending.slots.get("output_entity")
        answer = self._say(key, fields, lang, intent, dict(pending.slots))
        return Answer(
            answer.text,
            lang,
            intent,
            dict(pending.slots),
            action=pending.rule.action,
            display=output != "say",
            say=output != "display",
        )

    @staticmethod
    def _say(
        key: str, fields: dict[str, object], lang: str, intent: str, ents: dict[str, str]
    ) -> Answer:
        return Answer(phrase(key, lang, fields), lang, intent, ents, action=key)
