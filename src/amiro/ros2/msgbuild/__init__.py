"""Build ROS 2 interface packages that PyPI lacks from amiro's ``.msg``/``.action`` files.

``build_package("nav2_msgs")`` generates the sources with the installed rosidl generators,
compiles them with gcc/g++ and installs the package into the venv, so that
``from nav2_msgs.action import NavigateToPose`` works and rclpy can serve and call it,
wire-compatible with an upstream ROS 2 Jazzy install (same type names and type hashes).
Shipped: tf2_msgs, nav2_msgs, hri_msgs and amiro's own amiro_interfaces.  Run once by setup.
"""

from __future__ import annotations

import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

from amiro.ros2.msgbuild.compile import build, plan_targets
from amiro.ros2.msgbuild.generate import generate_sources
from amiro.ros2.msgbuild.install import install, is_current
from amiro.ros2.msgbuild.package import load_package
from amiro.ros2.types import INTERFACES_DIR

__all__ = ["BuildResult", "build_package"]


@dataclass(frozen=True)
class BuildResult:
    package: str
    prefix: Path
    skipped: bool  # already built from the same definitions
    seconds: float
    libraries: list[Path] = field(default_factory=list)


def build_package(
    name: str,
    prefix: Path | None = None,
    force: bool = False,
    interfaces_dir: Path = INTERFACES_DIR,
) -> BuildResult:
    """Build and install package ``name`` into ``prefix`` (default: this venv).

    The generators, the dependencies' headers and libraries come from this interpreter's
    prefix, where the ROS 2 wheels are installed.
    """
    ros_prefix = Path(sys.prefix)
    prefix = (prefix or ros_prefix).resolve()
    package = load_package(name, interfaces_dir)
    start = time.perf_counter()  # wall time only to report how long the build took
    if not force and is_current(package, prefix):
        return BuildResult(name, prefix, True, time.perf_counter() - start)
    with tempfile.TemporaryDirectory(prefix=f"amiro-msgbuild-{name}-") as tmp:
        build_dir = Path(tmp)
        sources = generate_sources(package, ros_prefix, build_dir)
        stage = build_dir / "stage"
        for target in plan_targets(sources, ros_prefix, stage):
            build(target, (stage / "lib", ros_prefix / "lib"))
        libraries = install(sources, stage, prefix)
    return BuildResult(name, prefix, False, time.perf_counter() - start, libraries)
