"""Understanding across processes: the NLU runs in the cloud, the Listen task on the edge.

The paper's section 3.1 puts dialogue among the cloud processes.  The cloud serves
``/amiro/dialogue/understand`` (a :class:`~amiro.core.messages.SpeechHeard` in, an
:class:`Understood` out) from its dialogue stack; on the edge, :class:`RemoteUnderstanding`
is the tasks' ``nlu`` module and calls that service through the bus, where
:class:`~amiro.ros2.services.RemoteService` stands for it.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass

from amiro.core.bus import Bus, BusError
from amiro.core.messages import SpeechHeard
from amiro.core.node import Node
from amiro.dialogue.ports import Understanding

UNDERSTAND_SERVICE = "/amiro/dialogue/understand"

log = logging.getLogger("amiro.ros2.dialogue")


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
        self.create_service(UNDERSTAND_SERVICE, self.understand)

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
            understood: Understood = self.bus.call(UNDERSTAND_SERVICE, heard)
        except BusError as exc:
            log.warning("understanding unavailable, answer taken as not understood: %s", exc)
            return "out_of_scope", 0.0
        return understood.intent, understood.confidence
