"""The real recordings of ``../shared/data`` (research terms: read beside the clone, never
copied into it).  Missing data skips a test on a developer's machine and fails it in CI
(``CI`` set), so CI can never pass by skipping the real-data checks."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def shared_data(*parts: str) -> Path:
    """``shared/data/<parts>`` from ``$AMIRO_SHARED`` or beside the checkout (a worktree may
    sit deeper: every parent folder is tried)."""
    env = os.environ.get("AMIRO_SHARED")
    bases = [Path(env)] if env else [parent / "shared" for parent in ROOT.parents]
    for base in bases:
        found = base.joinpath("data", *parts)
        if found.exists():
            return found
    message = f"shared/data/{'/'.join(parts)} not found beside {ROOT} (set AMIRO_SHARED)"
    if os.environ.get("CI"):
        pytest.fail(message)
    pytest.skip(message)
