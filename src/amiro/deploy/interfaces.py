"""The actions and services a split deployment offers over ROS 2, by name: the ROS 2 action
type each action travels as, the typed payloads each service carries."""

from __future__ import annotations

from typing import Any

from amiro.core import names
from amiro.core.config import ConfigError
from amiro.core.messages import SpeechHeard
from amiro.deploy.codecs import (
    BehaviorRunCodec,
    ForwardCodec,
    MoveToCodec,
    NavigateToPoseCodec,
    RecognizeActivityCodec,
    SearchCodec,
)
from amiro.deploy.dialogue import Understood
from amiro.ros2.interfaces import ActionCodec, ServiceSpec, service_spec

# by ROS 2 action name: /navigate_to_pose is MoveTo as Nav2's NavigateToPose
ACTIONS: dict[str, ActionCodec[Any, Any, Any]] = {
    codec.ros_name: codec
    for codec in (
        MoveToCodec(),
        ForwardCodec(),
        SearchCodec(),
        RecognizeActivityCodec(),
        BehaviorRunCodec(),
        NavigateToPoseCodec(),
    )
}


def known_action(name: str) -> ActionCodec[Any, Any, Any]:
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
