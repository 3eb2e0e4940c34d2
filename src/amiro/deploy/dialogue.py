"""Dialogue across processes: the NLU and the dialogue manager in the cloud, behaviours on
the edge.

The paper's section 3.1 puts dialogue among the cloud processes.  The cloud serves
``/amiro/dialogue/understand`` (a :class:`~amiro.core.messages.SpeechHeard` in, an
:class:`Understood` out) from its dialogue stack; on the edge, :class:`RemoteUnderstanding`
is the tasks' ``nlu`` module and calls that service through the bus, where
:class:`~amiro.ros2.services.RemoteService` stands for it.  The other way, a command the
cloud's dialogue manager understood ("go to the kitchen") goes to the edge as a behaviour
goal (:class:`DialogueBehaviors`), and the robot says how it ended.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass
from typing import Any

from amiro.core import names
from amiro.core.bus import Bus, BusError, Publisher
from amiro.core.messages import SpeechHeard, SpeechRequest
from amiro.core.node import Node
from amiro.deploy.behaviors import BehaviorGoal, BehaviorRequests, Request
from amiro.dialogue.ports import Understanding

log = logging.getLogger("amiro.deploy.dialogue")


@dataclass(frozen=True)
class Understood:
    """The answer of the understanding service: what :meth:`Understanding.intent` returns."""

    intent: str
    confidence: float


class UnderstandingService(Node):
    """Cloud side: offers an :class:`Understanding` (the dialogue stack's) as a bus service."""

    def __init__(self, understanding: Understanding) -> None:
        super().__init__("understanding_service")
        self.understanding = understanding
        self.answered: list[Understood] = []

    def on_start(self) -> None:
        self.create_service(names.UNDERSTAND, self.understand)

    def understand(self, heard: SpeechHeard) -> Understood:
        intent, confidence = self.understanding.intent(heard)
        self.answered.append(Understood(intent, confidence))
        return self.answered[-1]


class RemoteUnderstanding:
    """Edge side: the ``Understanding`` port answered by whoever serves the bus service.

    An unreachable cloud reads as an answer not understood, so Listen asks again rather
    than the behaviour failing."""

    def __init__(self, bus: Bus) -> None:
        self.bus = bus

    def intent(self, heard: SpeechHeard) -> tuple[str, float]:
        try:
            understood: Understood = self.bus.call(names.UNDERSTAND, heard)
        except BusError as exc:
            log.warning("understanding unavailable, answer taken as not understood: %s", exc)
            return "out_of_scope", 0.0
        return understood.intent, understood.confidence


# How a requested behaviour ended, said in the requester's language ({target}: the room or
# person asked for, {outcome}: the behaviour's end, e.g. "unreachable").
OUTCOME_PHRASES = {
    "done": {
        "en": "I have arrived: {target}.",
        "ro": "Am ajuns: {target}.",
        "fr": "Je suis arrivé : {target}.",
    },
    "failed": {
        "en": "I could not get to {target} ({outcome}).",
        "ro": "Nu am putut ajunge la {target} ({outcome}).",
        "fr": "Je n'ai pas pu aller à {target} ({outcome}).",
    },
}


def outcome_phrase(req: Request, lang: str) -> str:
    payload = req.goal.payload
    target = str(payload.get("person_entity") or payload.get("room_entity") or req.goal.kind)
    phrases = OUTCOME_PHRASES["done" if req.ok else "failed"]
    return phrases.get(lang, phrases["en"]).format(target=target, outcome=req.outcome)


class DialogueBehaviors:
    """Cloud side: the dialogue's ``submit`` (see :func:`amiro.dialogue.stack.build_dialogue`)
    as behaviour goals to the edge; when a behaviour ends, the robot says how, and the answer
    is kept in ``answers``.  No edge on the bus reads as a failed request, said at once."""

    def __init__(self, requests: BehaviorRequests, say: Publisher[SpeechRequest]) -> None:
        self.requests = requests
        self.say = say
        self.answers: list[dict[str, Any]] = []

    def __call__(self, kind: str, payload: dict[str, Any]) -> object:
        lang = str(payload.get("lang", "en"))
        goal = BehaviorGoal(kind, dict(payload))
        try:
            return self.requests.request(goal, lambda req: self._answer(req, lang))
        except BusError as exc:
            log.warning("behaviour %s not requested: %s", kind, exc)
            self._answer(Request("unsent", goal, self.requests.now(), outcome="no_edge"), lang)
            return None

    def _answer(self, req: Request, lang: str) -> None:
        text = outcome_phrase(req, lang)
        self.answers.append({"request": req.id, "outcome": req.outcome, "text": text})
        self.say.publish(SpeechRequest(text, lang, act="behavior_outcome"))
