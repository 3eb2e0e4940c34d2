"""Domain ids are claimed machine-wide, so concurrent runs never share a DDS domain."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from amiro.ros2.env import MAX_DOMAIN_ID, claimed_domain, ros_environment

HOLD = """
import sys, time
from pathlib import Path
from amiro.ros2.env import claimed_domain
with claimed_domain(lock_dir=Path(sys.argv[1])) as domain:
    print(domain, flush=True)
    time.sleep(60)
"""


def test_a_domain_held_elsewhere_is_skipped_and_freed_when_its_holder_dies(
    tmp_path: Path,
) -> None:
    holder = subprocess.Popen(
        [sys.executable, "-c", HOLD, str(tmp_path)], stdout=subprocess.PIPE, text=True
    )
    assert holder.stdout is not None
    held = int(holder.stdout.readline())
    with claimed_domain(lock_dir=tmp_path) as mine, claimed_domain(lock_dir=tmp_path) as next_:
        assert held == 1 and mine == 2 and next_ == 3
    holder.kill()
    holder.wait(timeout=10)
    with claimed_domain(lock_dir=tmp_path) as domain:
        assert domain == 1  # the lock died with its process


def test_all_domains_taken_is_a_clear_error(tmp_path: Path) -> None:
    last = claimed_domain(MAX_DOMAIN_ID, tmp_path)
    with last, pytest.raises(RuntimeError, match="in use"), claimed_domain(MAX_DOMAIN_ID, tmp_path):
        pass


def test_domain_ids_outside_the_valid_range_are_refused() -> None:
    assert ros_environment(MAX_DOMAIN_ID)["ROS_DOMAIN_ID"] == str(MAX_DOMAIN_ID)
    with pytest.raises(ValueError, match="domain id"):
        ros_environment(MAX_DOMAIN_ID + 1)
