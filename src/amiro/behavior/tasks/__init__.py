"""The task types of section 3.7; importing this package registers them."""

from amiro.behavior.tasks.activity import RecognizeActivity
from amiro.behavior.tasks.check import Check
from amiro.behavior.tasks.motion import MoveTo, Wait
from amiro.behavior.tasks.notify import NotifyEnvironment
from amiro.behavior.tasks.search import Search
from amiro.behavior.tasks.speech import Display, Listen, Say

__all__ = [
    "Check",
    "Display",
    "Listen",
    "MoveTo",
    "NotifyEnvironment",
    "RecognizeActivity",
    "Say",
    "Search",
    "Wait",
]
