"""The environment rclpy needs when installed from PyPI, set by amiro rather than by hand.

The ``ros-jazzy-*`` wheels find their shared libraries through ``ros_wheels_bootstrapper``
(a ``.pth`` hook that re-executes Python with ``LD_LIBRARY_PATH`` set), so amiro only
chooses the middleware, the domain and how far discovery reaches.  Tests and single-machine
deployments stay on loopback in their own ``ROS_DOMAIN_ID``.
"""

from __future__ import annotations

import fcntl
import os
import tempfile
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from pathlib import Path

RMW = "rmw_fastrtps_cpp"
MAX_DOMAIN_ID = 101  # the largest id whose DDS ports stay valid on Linux


def ros_environment(domain_id: int | None = None, localhost_only: bool = True) -> dict[str, str]:
    """The variables to give a process that talks ROS 2 (inherit the rest)."""
    env = {"RMW_IMPLEMENTATION": os.environ.get("RMW_IMPLEMENTATION", RMW)}
    if domain_id is not None:
        if not 0 <= domain_id <= MAX_DOMAIN_ID:
            raise ValueError(f"ROS domain id must be in 0..{MAX_DOMAIN_ID}, got {domain_id}")
        env["ROS_DOMAIN_ID"] = str(domain_id)
    # Jazzy's name for "discover on loopback only"; ROS_LOCALHOST_ONLY is deprecated there.
    env["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST" if localhost_only else "SUBNET"
    return env


def apply(env: Mapping[str, str]) -> None:
    """Set these variables in this process, before rclpy is initialised."""
    os.environ.update(env)
    os.environ.pop("ROS_LOCALHOST_ONLY", None)


@contextmanager
def claimed_domain(first: int = 1, lock_dir: Path | None = None) -> Iterator[int]:
    """A ROS domain id no other amiro process on this machine holds while the block runs.

    Concurrent test runs or deployments on one machine would otherwise discover each other
    in a shared domain; an advisory lock file per id keeps them apart (released on exit,
    also when the process dies)."""
    folder = lock_dir or Path(tempfile.gettempdir())
    for domain in range(first, MAX_DOMAIN_ID + 1):
        handle = (folder / f"amiro-ros-domain-{domain}.lock").open("a")
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            handle.close()
            continue
        try:
            yield domain
        finally:
            fcntl.flock(handle, fcntl.LOCK_UN)
            handle.close()
        return
    raise RuntimeError(f"every ROS domain id from {first} to {MAX_DOMAIN_ID} is in use here")
