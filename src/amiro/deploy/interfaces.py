"""The actions and services a split deployment offers over ROS 2, by name: the typed
payloads each one carries on the wire."""

from __future__ import annotations

from amiro.core import names
from amiro.core.config import ConfigError
from amiro.core.messages import SpeechHeard
from amiro.deploy.behaviors import BehaviorFeedback, BehaviorGoal, BehaviorResult
from amiro.deploy.dialogue import Understood
from amiro.navigation.move_to import MoveToFeedback, MoveToGoal, MoveToResult
from amiro.navigation.primitives import ForwardGoal, PrimitiveFeedback, PrimitiveResult
from amiro.ros2.interfaces import ActionSpec, ServiceSpec, action_spec, service_spec

ACTIONS: dict[str, ActionSpec] = {
    spec.name: spec
    for spec in (
        action_spec(
            names.MOVE_TO,
            MoveToGoal,
            MoveToFeedback,
            MoveToResult,
            lambda reason: MoveToResult(False, reason),
        ),
        action_spec(  # reframing for RecognizeActivity on an edge whose base is remote
            names.FORWARD,
            ForwardGoal,
            PrimitiveFeedback,
            PrimitiveResult,
            lambda reason: PrimitiveResult(False, reason),
        ),
        action_spec(
            names.BEHAVIOR_RUN,
            BehaviorGoal,
            BehaviorFeedback,
            BehaviorResult,
            lambda reason: BehaviorResult(False, reason),
        ),
    )
}


def known_action(name: str) -> ActionSpec:
    spec = ACTIONS.get(name)
    if spec is None:
        raise ConfigError(f"no ROS 2 action named {name} (known: {', '.join(sorted(ACTIONS))})")
    return spec


SERVICES: dict[str, ServiceSpec] = {
    spec.name: spec for spec in (service_spec(names.UNDERSTAND, SpeechHeard, Understood),)
}


def known_service(name: str) -> ServiceSpec:
    spec = SERVICES.get(name)
    if spec is None:
        raise ConfigError(f"no ROS 2 service named {name} (known: {', '.join(sorted(SERVICES))})")
    return spec
