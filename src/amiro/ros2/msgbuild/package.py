"""The interface packages amiro ships as ``.msg`` sources, and what each depends on.

ROS 2 message packages missing from PyPI (tf2_msgs, audio_common_msgs) are kept in
``amiro/data/ros2_interfaces/<package>/msg/`` with their upstream licence; the packages
their fields refer to (geometry_msgs...) must already be installed in the ROS prefix.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass
from pathlib import Path

from rosidl_adapter.parser import parse_message_string

from amiro.core.config import ConfigError
from amiro.ros2.types import INTERFACES_DIR


@dataclass(frozen=True)
class InterfacePackage:
    name: str
    source_dir: Path  # holds msg/*.msg
    messages: tuple[Path, ...]  # relative to source_dir: msg/TFMessage.msg
    dependencies: tuple[str, ...]  # packages the fields refer to, sorted

    @property
    def fingerprint(self) -> str:
        """Changes whenever a definition changes, so an old build is not taken for current."""
        digest = hashlib.sha256()
        for rel in self.messages:
            digest.update(rel.as_posix().encode() + b"\0")
            digest.update((self.source_dir / rel).read_bytes())
        return digest.hexdigest()[:16]


def shipped_packages() -> list[str]:
    return sorted(p.name for p in INTERFACES_DIR.iterdir() if (p / "msg").is_dir())


def load_package(name: str, interfaces_dir: Path = INTERFACES_DIR) -> InterfacePackage:
    source_dir = interfaces_dir / name
    messages = tuple(sorted(p.relative_to(source_dir) for p in source_dir.glob("msg/*.msg")))
    if not messages:
        known = ", ".join(shipped_packages()) or "none"
        raise ConfigError(f"no interface package {name!r} in {interfaces_dir} (shipped: {known})")
    deps: set[str] = set()
    for rel in messages:
        spec = parse_message_string(name, rel.stem, (source_dir / rel).read_text("utf-8"))
        deps.update(
            f.type.pkg_name
            for f in spec.fields
            if not f.type.is_primitive_type() and f.type.pkg_name != name
        )
    return InterfacePackage(name, source_dir, messages, tuple(sorted(deps)))
