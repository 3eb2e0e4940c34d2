"""Robot-adapter tests talk ROS 2 on loopback in domains of their own, or NAOqi on loopback."""

from __future__ import annotations

import itertools
import os

import pytest

_domains = itertools.count(30 + os.getpid() % 25)


@pytest.fixture
def robot_domain() -> int:
    return next(_domains)
