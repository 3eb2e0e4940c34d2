"""The dashboard's chat box talks to the dialogue module through this small port."""

from __future__ import annotations

from typing import Protocol

LANGUAGES = ("en", "ro", "fr")


class ChatPort(Protocol):
    def reply(self, text: str, lang: str) -> str:
        """The robot's answer to ``text`` said in ``lang`` (en, ro or fr)."""
        ...


UNAVAILABLE = {
    "en": "The dialogue module is not connected, so I cannot answer yet.",
    "ro": "Modulul de dialog nu este conectat, așa că încă nu pot răspunde.",
    "fr": "Le module de dialogue n'est pas connecté, je ne peux donc pas encore répondre.",
}


class UnavailableChat:
    """Until a dialogue backend is wired in: says so plainly instead of inventing answers."""

    def reply(self, text: str, lang: str) -> str:
        return UNAVAILABLE.get(lang, UNAVAILABLE["en"])
