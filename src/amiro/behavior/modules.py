"""The modules behaviour tasks call, each typed by the port it serves.

The assembly (:mod:`amiro.system`, a deployment's edge) fills in what runs in its process; a
task asks for what it needs with :meth:`~amiro.behavior.task.TaskContext.need`, which fails
the task with a clear error when that module is not running there.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

from amiro.activity.ports import ActivityRecognizer
from amiro.behavior.planning.knowledge import KnowledgeBase
from amiro.core.clock import Clock
from amiro.core.messages import Pose2D
from amiro.dialogue.ports import SpeechOutput, Understanding
from amiro.home.world import World
from amiro.perception.ports import PeopleFinder


class Localized(Protocol):
    """Navigation as tasks read it: where the robot is and how it moves."""

    @property
    def pose(self) -> Pose2D | None: ...

    @property
    def velocity(self) -> tuple[float, float, float]: ...


@dataclass
class Modules:
    """What a task may call; None: not running in this process."""

    clock: Clock | None = None
    world: World | None = None
    navigation: Localized | None = None
    perception: PeopleFinder | None = None
    activity: ActivityRecognizer | None = None
    speech: SpeechOutput | None = None
    nlu: Understanding | None = None
    knowledge: KnowledgeBase | None = None
