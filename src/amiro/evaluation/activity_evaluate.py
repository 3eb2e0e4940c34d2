"""``amiro har evaluate``: the paper's Table 15 protocols on held-out synthetic data or NTU.

Cross-subject scores subjects never trained on, cross-view camera positions never trained
on; the missing-joint rows hide the same random share of joints over a whole window;
``pose_estimator`` scores the cross-subject windows as a robot without a Kinect rebuilds
them (2D BODY_25 keypoints on Pepper's head camera, lifted with the depth image), and
``pose_estimator_coco17`` a third of them through COCO-17 keypoints (a YOLO-pose model:
no feet) with the head pitched down by 0.2 rad (the ``camera-onnx`` backend's path).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from amiro.activity.augment import drop_joints
from amiro.activity.dataset import (
    TEST_CAMERAS_DEG,
    TEST_SUBJECTS,
    TRAIN_CAMERAS_DEG,
    TRAIN_SUBJECTS,
    generate,
)
from amiro.activity.labels import ACTIONS, NTU_ACTION_IDS
from amiro.activity.ntu import NTU_NAME, read_skeleton_file
from amiro.activity.onnx_model import ActivityModel
from amiro.activity.render import through_pose_estimator
from amiro.activity.skeleton import FloatArray
from amiro.core.config import ConfigError
from amiro.robot.camera import Camera

EVAL_FRAMES = 30  # 2 s at the model's 15 Hz
MISSING_FRACTIONS = (0.1, 0.2, 0.3, 0.5)
COCO_PITCH = 0.2  # rad down: the head looking at a person 2-3 m away
PAPER = {"cross_subject": 0.9227, "cross_view": 0.9163}
TARGETS = {"cross_subject": 0.95, "cross_view": 0.95, "missing_joints_0.3": 0.85}
# NTU RGB+D's cross-subject training performers; the others are its test subjects.
NTU_TRAIN_SUBJECTS = frozenset(
    (1, 2, 4, 5, 8, 9, 13, 14, 15, 16, 17, 18, 19, 25, 27, 28, 31, 34, 35, 38)
)
NTU_TEST_CAMERA = 1


def predict(model: ActivityModel, windows: list[FloatArray], batch: int = 256) -> np.ndarray:
    """Predicted class per window; windows of equal length are batched."""
    out = np.empty(len(windows), dtype=np.int64)
    for length in {len(w) for w in windows}:
        idx = [i for i, w in enumerate(windows) if len(w) == length]
        for s in range(0, len(idx), batch):
            part = idx[s : s + batch]
            probs = model.classify_batch(np.stack([windows[i] for i in part]))
            out[part] = probs.argmax(axis=1)
    return out


def confusion(labels: np.ndarray, predicted: np.ndarray) -> dict[str, Any]:
    matrix = np.zeros((len(ACTIONS), len(ACTIONS)), dtype=np.int64)
    np.add.at(matrix, (labels, predicted), 1)
    return {"labels": list(ACTIONS), "matrix": matrix.tolist()}


def _accuracy(model: ActivityModel, windows: list[FloatArray], labels: np.ndarray) -> float:
    if not windows:
        return float("nan")
    return float((predict(model, windows) == labels).mean())


def _missing(
    model: ActivityModel, windows: list[FloatArray], labels: np.ndarray, seed: int
) -> dict[str, float]:
    rng = np.random.default_rng(seed)
    return {
        str(p): round(_accuracy(model, [drop_joints(w, p, rng) for w in windows], labels), 4)
        for p in MISSING_FRACTIONS
    }


def _check_classes(model: ActivityModel) -> None:
    if model.classes != ACTIONS:
        raise ConfigError(f"{model.path}: classes {model.classes} are not amiro's {ACTIONS}")


def evaluate_synthetic(model: ActivityModel, seed: int = 1000) -> dict[str, Any]:
    """Accuracy on fresh synthetic windows from held-out subjects and held-out views."""
    _check_classes(model)
    rng = np.random.default_rng(seed)
    cs = generate(TEST_SUBJECTS, TRAIN_CAMERAS_DEG, 2, rng)
    cv = generate(TRAIN_SUBJECTS, TEST_CAMERAS_DEG, 1, rng)
    cs_windows = list(cs.frames[:, -EVAL_FRAMES:])
    cv_windows = list(cv.frames[:, -EVAL_FRAMES:])
    cs_pred = predict(model, cs_windows)
    info = Camera().info(0.0)  # Pepper's head camera
    rebuilt = [through_pose_estimator(w, info) for w in cs_windows]
    coco = [through_pose_estimator(w, info, "coco17", COCO_PITCH) for w in cs_windows[::3]]
    return {
        "data": "synthetic",
        "cross_subject": round(float((cs_pred == cs.labels).mean()), 4),
        "cross_view": round(_accuracy(model, cv_windows, cv.labels), 4),
        "confusion": confusion(cs.labels, cs_pred),
        "missing_joints": _missing(model, cs_windows, cs.labels, seed),
        "pose_estimator": round(_accuracy(model, rebuilt, cs.labels), 4),
        "pose_estimator_coco17": round(_accuracy(model, coco, cs.labels[::3]), 4),
        "samples": {"cross_subject": len(cs), "cross_view": len(cv)},
        "frames": EVAL_FRAMES,
        "paper": PAPER,
        "targets": TARGETS,
    }


def evaluate_ntu(model: ActivityModel, folder: Path, seed: int = 1000) -> dict[str, Any]:
    """The same metrics on real NTU RGB+D files of amiro's nine actions (30 Hz -> 15 Hz)."""
    _check_classes(model)
    if not folder.is_dir():
        raise ConfigError(f"{folder}: no such folder")
    by_id = {ntu: ACTIONS.index(name) for name, ntu in NTU_ACTION_IDS.items()}
    windows: list[FloatArray] = []
    labels, subjects, cameras = [], [], []
    for path in sorted(folder.rglob("*.skeleton")):
        m = NTU_NAME.search(path.name)
        if m is None or int(m.group(5)) not in by_id:
            continue
        body = read_skeleton_file(path).main_body()
        frames = body.joints[body.present][::2]
        if len(frames) == 0:
            continue
        windows.append(frames)
        labels.append(by_id[int(m.group(5))])
        cameras.append(int(m.group(2)))
        subjects.append(int(m.group(3)))
    if not windows:
        ids = ", ".join(f"A{i:03d}" for i in sorted(by_id))
        raise ConfigError(f"{folder}: no NTU .skeleton files of the actions {ids}")
    y = np.array(labels)
    pred = predict(model, windows)
    cs = np.array([s not in NTU_TRAIN_SUBJECTS for s in subjects])
    cv = np.array(cameras) == NTU_TEST_CAMERA
    cs_windows = [w for w, keep in zip(windows, cs, strict=True) if keep]

    def acc(mask: np.ndarray) -> float | None:
        return round(float((pred[mask] == y[mask]).mean()), 4) if mask.any() else None

    return {
        "data": "ntu",
        "files": len(windows),
        "cross_subject": acc(cs),
        "cross_view": acc(cv),
        "all": acc(np.ones(len(y), bool)),
        "confusion": confusion(y, pred),
        "missing_joints": _missing(model, cs_windows, y[cs], seed) if cs_windows else {},
        "paper": PAPER,
    }


def format_report(report: dict[str, Any]) -> str:
    lines = [
        f"data: {report['data']}",
        f"cross-subject accuracy: {report['cross_subject']} (paper {PAPER['cross_subject']})",
        f"cross-view accuracy:    {report['cross_view']} (paper {PAPER['cross_view']})",
    ]
    for p, acc in report["missing_joints"].items():
        lines.append(f"{float(p):.0%} joints missing: {acc}")
    if "pose_estimator" in report:
        lines.append(f"through 2D keypoints + depth: {report['pose_estimator']}")
        lines.append(f"through COCO-17 keypoints, head pitched: {report['pose_estimator_coco17']}")
    labels = report["confusion"]["labels"]
    lines.append("confusion (rows: true, columns: predicted):")
    for name, row in zip(labels, report["confusion"]["matrix"], strict=True):
        lines.append(f"  {name:>13} " + " ".join(f"{v:4d}" for v in row))
    return "\n".join(lines)
