"""The interface packages amiro ships as ``.msg``/``.srv``/``.action`` sources, and what each
depends on.

ROS 2 interface packages missing from PyPI (tf2_msgs, audio_common_msgs, nav2_msgs, hri_msgs)
and amiro's own (amiro_interfaces) are kept in
``amiro/data/ros2_interfaces/<package>/{msg,srv,action}/`` with their upstream licence; the
packages their fields refer to (geometry_msgs...) must already be installed in the ROS prefix.
Services and actions also depend on the packages rosidl's expansion of them uses (the service
event, the goal id, the goal status).
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass
from pathlib import Path

from rosidl_adapter.parser import (
    MessageSpecification,
    parse_action_string,
    parse_message_string,
    parse_service_string,
)

from amiro.core.config import ConfigError
from amiro.ros2.types import INTERFACES_DIR

KINDS = {"msg": ".msg", "srv": ".srv", "action": ".action"}
# what rosidl's expansion of a service (its event message) or an action brings in
IMPLIED = {
    "srv": ("builtin_interfaces", "service_msgs"),
    "action": ("action_msgs", "builtin_interfaces", "service_msgs", "unique_identifier_msgs"),
}


@dataclass(frozen=True)
class InterfacePackage:
    name: str
    source_dir: Path  # holds msg/*.msg, srv/*.srv, action/*.action
    interfaces: tuple[Path, ...]  # relative to source_dir: msg/TFMessage.msg
    dependencies: tuple[str, ...]  # packages the fields refer to, sorted

    @property
    def kinds(self) -> tuple[str, ...]:
        """The interface kinds present (``msg``, ``srv``, ``action``), in that order."""
        present = {rel.parts[0] for rel in self.interfaces}
        return tuple(k for k in KINDS if k in present)

    @property
    def fingerprint(self) -> str:
        """Changes whenever a definition changes, so an old build is not taken for current."""
        digest = hashlib.sha256()
        for rel in self.interfaces:
            digest.update(rel.as_posix().encode() + b"\0")
            digest.update((self.source_dir / rel).read_bytes())
        return digest.hexdigest()[:16]


def shipped_packages() -> list[str]:
    return sorted(
        p.name for p in INTERFACES_DIR.iterdir() if any((p / kind).is_dir() for kind in KINDS)
    )


def _specs(package: str, rel: Path, text: str) -> list[MessageSpecification]:
    """The message specifications one definition file holds (three for an action)."""
    kind, stem = rel.parts[0], rel.stem
    if kind == "msg":
        return [parse_message_string(package, stem, text)]
    if kind == "srv":
        srv = parse_service_string(package, stem, text)
        return [srv.request, srv.response]
    action = parse_action_string(package, stem, text)
    return [action.goal, action.result, action.feedback]


def load_package(name: str, interfaces_dir: Path = INTERFACES_DIR) -> InterfacePackage:
    source_dir = interfaces_dir / name
    interfaces = tuple(
        sorted(
            p.relative_to(source_dir)
            for kind, suffix in KINDS.items()
            for p in source_dir.glob(f"{kind}/*{suffix}")
        )
    )
    if not interfaces:
        known = ", ".join(shipped_packages()) or "none"
        raise ConfigError(f"no interface package {name!r} in {interfaces_dir} (shipped: {known})")
    deps: set[str] = set()
    for rel in interfaces:
        for spec in _specs(name, rel, (source_dir / rel).read_text("utf-8")):
            deps.update(
                f.type.pkg_name
                for f in spec.fields
                if not f.type.is_primitive_type() and f.type.pkg_name != name
            )
        deps.update(IMPLIED.get(rel.parts[0], ()))
    return InterfacePackage(name, source_dir, interfaces, tuple(sorted(deps)))
