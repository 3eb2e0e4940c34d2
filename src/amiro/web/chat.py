"""The dashboard's chat box talks to the dialogue module through this small port."""

from __future__ import annotations

from typing import Protocol

from amiro.dialogue.manager import DialogueManager


class ChatPort(Protocol):
    def reply(self, text: str, lang: str, user: str) -> str:
        """The robot's answer to ``text`` said by ``user`` in ``lang`` (en, ro or fr); called
        on the runtime's thread, since answering may act on the home or the robot."""
        ...


class DialogueChat:
    """The system's dialogue manager: one conversation per user (a question it asks back,
    "in which room?", waits for that user's next message), answers in the user's language."""

    def __init__(self, manager: DialogueManager) -> None:
        self.manager = manager

    def reply(self, text: str, lang: str, user: str) -> str:
        return self.manager.handle(text, lang, user).text
