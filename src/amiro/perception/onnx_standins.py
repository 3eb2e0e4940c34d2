"""ONNX models generated with the ``onnx`` package, standing in for a user's detector or pose
model where none may be downloaded: in tests (a model that always answers known rows) and
in the camera benchmark (random weights with a small YOLO's compute, so inference is timed
at a realistic cost).  The layouts are the ones :mod:`amiro.perception.onnx_yolo` and
:mod:`amiro.activity.pose` read.
"""

from __future__ import annotations

import importlib
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from amiro.core.config import ConfigError

# Backbone of the benchmark's stand-in: (output channels, stride, extra 3x3 convs).
STAGES = ((16, 2, 0), (32, 2, 1), (64, 2, 3), (128, 2, 1), (256, 2, 1))


def _onnx() -> Any:
    try:
        return importlib.import_module("onnx")
    except ImportError as exc:
        raise ConfigError(f"generating a stand-in model needs the onnx package: {exc}") from None


def _save(onnx: Any, graph: Any, path: Path) -> Path:
    model = onnx.helper.make_model(graph, opset_imports=[onnx.helper.make_opsetid("", 13)])
    model.ir_version = 8
    onnx.checker.check_model(model)
    onnx.save(model, str(path))
    return path


def fixed_answer_model(
    path: Path, rows: npt.NDArray[Any], size: int = 320, channels_first: bool = False
) -> Path:
    """A model with YOLO's input ``(1, 3, size, size)`` that always outputs ``rows``
    ``(N, C)`` as ``(1, N, C)``, or ``(1, C, N)`` when ``channels_first`` (YOLOv8's)."""
    onnx = _onnx()
    h, t = onnx.helper, onnx.TensorProto
    answer = np.asarray(rows, dtype=np.float32)
    answer = (answer.T if channels_first else answer)[None]
    graph = h.make_graph(
        [h.make_node("Identity", ["answer"], ["output0"])],
        "fixed_answer",
        [h.make_tensor_value_info("images", t.FLOAT, [1, 3, size, size])],
        [h.make_tensor_value_info("output0", t.FLOAT, list(answer.shape))],
        initializer=[onnx.numpy_helper.from_array(np.ascontiguousarray(answer), "answer")],
    )
    return _save(onnx, graph, path)


def standin_yolo(
    path: Path, outputs: int, rng: np.random.Generator, size: int = 640, width: float = 1.0
) -> tuple[Path, float]:
    """A random-weight convolutional network from ``(1, 3, size, size)`` to YOLO rows
    ``(1, N, outputs)`` (N = (size / 32)^2), its channels ``width`` times :data:`STAGES`';
    returns the path and its GFLOPs."""
    onnx = _onnx()
    h, t = onnx.helper, onnx.TensorProto
    nodes: list[Any] = []
    weights: list[Any] = []
    name, channels, side, macs = "images", 3, size, 0

    def conv(out: int, kernel: int, stride: int) -> None:
        nonlocal name, channels, side, macs
        w = f"w{len(weights)}"
        scale = np.sqrt(2.0 / (channels * kernel * kernel))
        tensor = rng.standard_normal((out, channels, kernel, kernel)) * scale
        weights.append(onnx.numpy_helper.from_array(tensor.astype(np.float32), w))
        pad = (kernel - stride + 1) // 2 if stride > 1 else kernel // 2
        side //= stride
        macs += side * side * out * channels * kernel * kernel
        nodes.append(
            h.make_node(
                "Conv", [name, w], [w + "_c"], kernel_shape=[kernel] * 2, strides=[stride] * 2,
                pads=[pad] * 4,
            )
        )  # fmt: skip
        nodes.append(h.make_node("Relu", [w + "_c"], [w + "_r"]))
        name, channels = w + "_r", out

    for out, stride, extra in STAGES:
        conv(round(out * width), 3, stride)
        for _ in range(extra):
            conv(round(out * width), 3, 1)
    conv(outputs, 1, 1)
    shape = onnx.numpy_helper.from_array(np.array([1, outputs, -1], dtype=np.int64), "shape")
    nodes += [
        h.make_node("Sigmoid", [name], ["probs"]),
        h.make_node("Reshape", ["probs", "shape"], ["flat"]),
        h.make_node("Transpose", ["flat"], ["output0"], perm=[0, 2, 1]),
    ]
    cells = side * side
    graph = h.make_graph(
        nodes,
        "standin_yolo",
        [h.make_tensor_value_info("images", t.FLOAT, [1, 3, size, size])],
        [h.make_tensor_value_info("output0", t.FLOAT, [1, cells, outputs])],
        initializer=[*weights, shape],
    )
    return _save(onnx, graph, path), 2.0 * macs / 1e9
