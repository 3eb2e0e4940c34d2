"""A tiny model trained for a few steps, shared by the tests that need an ONNX file, and
the real skeleton sets (research data kept beside the clone, never in it)."""

from __future__ import annotations

from pathlib import Path

import pytest

from amiro.activity.onnx_model import ActivityModel
from amiro.activity.train import TrainConfig, train
from shared_data import shared_data


@pytest.fixture(scope="session")
def tiny_model(tmp_path_factory: pytest.TempPathFactory) -> ActivityModel:
    out: Path = tmp_path_factory.mktemp("har") / "tiny.onnx"
    train(TrainConfig(out=out, epochs=1, hidden=16, per_cell=1, max_steps=3, progress=False))
    return ActivityModel(out)


@pytest.fixture(scope="session")
def real_har() -> Path:
    """The real skeleton sets, ``shared/data/har`` beside the repository."""
    return shared_data("har")


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
