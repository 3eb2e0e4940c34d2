"""A tiny model trained for a few steps, shared by the tests that need an ONNX file, and
the real skeleton sets (research data kept beside the clone, never in it)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from amiro.activity.onnx_model import ActivityModel
from amiro.activity.train import TrainConfig, train


@pytest.fixture(scope="session")
def tiny_model(tmp_path_factory: pytest.TempPathFactory) -> ActivityModel:
    out: Path = tmp_path_factory.mktemp("har") / "tiny.onnx"
    train(TrainConfig(out=out, epochs=1, hidden=16, per_cell=1, max_steps=3, progress=False))
    return ActivityModel(out)


@pytest.fixture(scope="session")
def real_har() -> Path:
    """``shared/data/har`` beside the repository (CI: ``../shared``; a worktree may sit one
    folder deeper).  Missing in CI is a failure, not a skip."""
    root = Path(__file__).resolve().parents[2]
    for parent in root.parents:
        found = parent / "shared" / "data" / "har"
        if found.is_dir():
            return found
    if os.environ.get("CI"):
        pytest.fail(f"no shared/data/har beside {root}: CI must provide ../shared")
    pytest.skip(f"no shared/data/har beside {root} (real skeleton sets)")


@pytest.fixture(scope="session")
def tiny_open_set_model(tmp_path_factory: pytest.TempPathFactory, real_har: Path) -> ActivityModel:
    """A few steps on the real sets too: the ``unknown`` outcome and a validated threshold."""
    out: Path = tmp_path_factory.mktemp("har_open") / "tiny.onnx"
    train(
        TrainConfig(
            out=out, epochs=1, hidden=16, per_cell=1, max_steps=3, progress=False, real=real_har
        )
    )
    return ActivityModel(out)
