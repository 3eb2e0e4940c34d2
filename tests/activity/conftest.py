"""A tiny model trained for a few steps, shared by the tests that need an ONNX file."""

from __future__ import annotations

from pathlib import Path

import pytest

from amiro.activity.onnx_model import ActivityModel
from amiro.activity.train import TrainConfig, train


@pytest.fixture(scope="session")
def tiny_model(tmp_path_factory: pytest.TempPathFactory) -> ActivityModel:
    out: Path = tmp_path_factory.mktemp("har") / "tiny.onnx"
    train(TrainConfig(out=out, epochs=1, hidden=16, per_cell=1, max_steps=3, progress=False))
    return ActivityModel(out)
