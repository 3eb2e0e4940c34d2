"""Each test talks ROS 2 on loopback in a domain of its own (claimed machine-wide)."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from amiro.ros2.env import claimed_domain


@pytest.fixture
def domain_id() -> Iterator[int]:
    with claimed_domain() as domain:
        yield domain
