"""Each test talks ROS 2 on loopback in a domain of its own."""

from __future__ import annotations

import itertools
import os

import pytest

_domains = itertools.count(60 + os.getpid() % 30)


@pytest.fixture
def domain_id() -> int:
    return next(_domains)
