"""Dialogue management: the stories (memoization over the last turns) or else the rules pick
the next action, slots are carried across turns and missing ones asked for, a follow-up no
story explains gets the fallback, and every answer comes in the user's language with the
paper's default output (display and say unless the user asked for one of them)."""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field

from amiro.dialogue.actions import Actions
from amiro.dialogue.domain import Domain, Rule
from amiro.dialogue.phrases import phrase
from amiro.dialogue.stories import INFORM, MAX_HISTORY, Memoization, Stories, shipped_stories
from amiro.dialogue.understanding import Nlu

CANCEL_INTENTS = ("deny", "goodbye")
FALLBACK = "utter_fallback"


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
    stories: Stories = field(default_factory=shipped_stories)
    _pending: dict[str, _Pending] = field(default_factory=dict)
    _events: dict[str, list[str]] = field(default_factory=dict)  # per user, for the stories
    _slots: dict[str, dict[str, str]] = field(default_factory=dict)  # the last action's
    _memo: dict[str, Memoization] = field(default_factory=dict)  # per language

    def memo(self, lang: str) -> Memoization:
        """The memoization of ``lang``'s stories (the shared ones and its own)."""
        if lang not in self._memo:
            self._memo[lang] = Memoization(self.stories.of(lang))
        return self._memo[lang]

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
            answer = self._next_action(text, lang, user, parsed.intent, parsed.entities)
        self._remember(user, answer)
        self.history.append(Turn(user, text, answer))
        return answer

    def _next_action(
        self, text: str, lang: str, user: str, intent: str, entities: dict[str, str]
    ) -> Answer:
        """A story continued by this turn, else the rule for its intent, else the fallback."""
        followup = self.stories.is_followup(text, lang)
        turn = INFORM if followup else intent
        found = self.memo(lang).predict([*self._events.get(user, []), f"intent:{turn}"])
        rule = self.domain.for_action(found[0]) if found is not None else None
        if found is not None and rule is not None:
            heard = {e.key: e.value for e in self.nlu.entities(text, lang, found[1])}
            slots = {**rule.defaults, **self._slots.get(user, {}), **heard}
            return self._advance(_Pending(rule, slots, ""), lang, user, turn, slots)
        rule = None if followup else self.domain.rule(intent)
        if rule is None:
            return self._say(FALLBACK, {}, lang, turn, entities)
        slots = {**rule.defaults, **entities}
        return self._advance(_Pending(rule, slots, ""), lang, user, intent, slots)

    def _remember(self, user: str, answer: Answer) -> None:
        """The turn's events for the stories and, once an action ran, its slots to carry."""
        events = self._events.setdefault(user, [])
        events.append(f"intent:{INFORM if answer.intent == INFORM else answer.intent}")
        if answer.action:
            events.append(f"action:{answer.action}")
        del events[:-MAX_HISTORY]
        if answer.action and not answer.ask:
            carried = {k: v for k, v in answer.entities.items() if k != "output_entity"}
            self._slots[user] = carried

    def _advance(
        self, pending: _Pending, lang: str, user: str, intent: str, entities: dict[str, str]
    ) -> Answer:
        missing = pending.rule.missing(pending.slots)
        if missing:
            pending.asking = missing[0]
            self._pending[user] = pending
            key = self.domain.ask.get(missing[0], "utter_not_understood")
            text = phrase(key, lang, own=self.domain.responses)
            return Answer(text, lang, intent, entities, ask=missing[0])
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

    def _say(
        self, key: str, fields: dict[str, object], lang: str, intent: str, ents: dict[str, str]
    ) -> Answer:
        text = phrase(key, lang, fields, self.domain.responses)
        return Answer(text, lang, intent, ents, action=key)
