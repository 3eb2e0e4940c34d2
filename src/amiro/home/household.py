"""The people a robot lives with: one person type and the languages amiro speaks.

The simulator's residents extend :class:`Person` with where they are and what they do; a real
robot's household is configured as plain persons (``household:`` in the system config).
"""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from amiro.core.config import Section

Language = Literal["en", "ro", "fr"]
LANGUAGES: tuple[Language, ...] = ("en", "ro", "fr")


class Person(Section):
    """Someone the robot serves: how to address them and in which language and voice."""

    name: str
    language: Language = "en"
    voice: str = Field(default="", description="TTS voice; empty: the language's default")
