"""``amiro har train``: train the multi-stage LSTM and export ONNX.

With ``real`` (the folder of the real Kinect skeleton sets) the model learns amiro's
activities from real people where the sets have them, an ``unknown`` outcome from their
other actions, and picks its confidence threshold on held-out validation subjects
(:data:`amiro.activity.real_sets.ROLES`); synthetic motion (every class, the simulated
residents' too) is mixed in.  Without it, synthetic motion only.  Seeded end to end
(data, augmentation, weights, batch order); a progress bar on stderr; a checkpoint after
every epoch.  Needs the ``train`` extra (torch); the runtime does not.
"""

from __future__ import annotations

import json
import sys
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
import torch
from torch import nn
from tqdm import tqdm

from amiro.activity.augment import augment_real, augment_synthetic, time_warp
from amiro.activity.dataset import TRAIN_CAMERAS_DEG, TRAIN_SUBJECTS, WINDOW, generate
from amiro.activity.labels import ACTIONS, UNKNOWN
from amiro.activity.model import LastFrameProbabilities, MultiStageLSTM
from amiro.activity.motion import FPS
from amiro.activity.normalize import FEATURES_PER_FRAME, preprocess_batch
from amiro.activity.onnx_model import BOX_HEIGHT_RANGE, DEFAULT_THRESHOLD, METADATA_KEY
from amiro.activity.open_set import choose_decision, clip_windows, hide_joints
from amiro.activity.real_sets import Clip, load, role

REAL_STRIDE = 10  # frames between real training windows
VALIDATION_FRAMES = 30  # the recogniser's window


@dataclass(frozen=True)
class TrainConfig:
    out: Path
    epochs: int = 40
    batch: int = 64
    hidden: int = 64
    lr: float = 2e-3
    seed: int = 0
    per_cell: int = 6  # windows per (subject, camera, action)
    max_steps: int | None = None  # stop early (tests)
    min_length: int = 16  # training windows are cropped to min_length..WINDOW frames
    progress: bool = True
    checkpoints: Path | None = None  # default: a checkpoints/ folder beside ``out``
    real: Path | None = None  # the real skeleton sets (kard/, florence3d/, cad60/, citi/)
    stages: int = 3  # the paper's three
    speed: tuple[float, float] = (0.7, 1.4)  # time-warp range of the training windows


@dataclass
class _Data:
    frames: np.ndarray  # (N, WINDOW, 25, 3)
    labels: np.ndarray  # (N,) index into the classes
    real: np.ndarray  # (N,) bool: augmented as real windows

    def __len__(self) -> int:
        return len(self.labels)


def _batch(
    frames: np.ndarray,
    real: np.ndarray,
    rng: np.random.Generator,
    min_length: int,
    speed: tuple[float, float],
) -> torch.Tensor:
    length = int(rng.integers(min_length, WINDOW + 1))
    cropped = np.stack(
        [
            (augment_real if r else augment_synthetic)(
                time_warp(f, length, rng.uniform(*speed), rng), rng
            )
            for f, r in zip(frames, real, strict=True)
        ]
    )
    return torch.from_numpy(preprocess_batch(cropped))


def _loss(
    logits: torch.Tensor, labels: torch.Tensor, weights: torch.Tensor | None = None
) -> torch.Tensor:
    """Cross-entropy of every stage over the last quarter of the window's frames."""
    stages, batch, frames, classes = logits.shape
    tail = logits[:, :, -max(1, frames // 4) :]
    target = labels[None, :, None].expand(stages, batch, tail.shape[2])
    loss = nn.functional.cross_entropy(
        tail.reshape(-1, classes), target.reshape(-1), weight=weights
    )
    return loss * stages


def _data(cfg: TrainConfig, rng: np.random.Generator) -> tuple[_Data, tuple[str, ...], list[Clip]]:
    synthetic = generate(TRAIN_SUBJECTS, TRAIN_CAMERAS_DEG, cfg.per_cell, rng, seed=cfg.seed)
    if cfg.real is None:
        return (
            _Data(synthetic.frames, synthetic.labels, np.zeros(len(synthetic), bool)),
            ACTIONS,
            [],
        )
    classes = (*ACTIONS, UNKNOWN)
    clips = load(cfg.real, progress=cfg.progress)
    frames, labels = clip_windows(
        [c for c in clips if role(c) == "train"], classes, WINDOW, REAL_STRIDE
    )
    validation = [c for c in clips if role(c) == "validation"]
    data = _Data(
        np.concatenate([synthetic.frames, frames]),
        np.concatenate([synthetic.labels, labels]),
        np.concatenate([np.zeros(len(synthetic), bool), np.ones(len(labels), bool)]),
    )
    return data, classes, validation


def train(cfg: TrainConfig) -> dict[str, object]:
    """Train, checkpoint each epoch next to ``cfg.out``, export ``cfg.out`` (ONNX)."""
    torch.manual_seed(cfg.seed)
    torch.set_num_threads(1)  # small batches: a second thread only adds contention
    rng = np.random.default_rng(cfg.seed)
    data, classes, validation = _data(cfg, rng)
    counts = np.bincount(data.labels, minlength=len(classes)).astype(np.float64)
    # Rare classes weigh more (inverse square root of their share): CAD-60's long takes
    # would otherwise make ``unknown`` the easy answer.  (Fully inverse weights made every
    # real clip of a known class come out ``unknown``: the rare real classes' noisy losses
    # drove the validated threshold to 0.85.)
    inverse = 1.0 / np.sqrt(np.maximum(counts, 1.0))
    weights = torch.tensor(inverse / inverse.mean(), dtype=torch.float32)
    model = MultiStageLSTM(FEATURES_PER_FRAME, len(classes), cfg.hidden, cfg.stages)
    optim = torch.optim.Adam(model.parameters(), lr=cfg.lr)
    per_epoch = int(np.ceil(len(data) / cfg.batch))
    sched = torch.optim.lr_scheduler.OneCycleLR(
        optim, max_lr=cfg.lr, total_steps=max(cfg.epochs * per_epoch, 1)
    )
    labels = torch.from_numpy(data.labels)
    ckpt_dir = cfg.checkpoints or cfg.out.parent / "checkpoints"
    ckpt_dir.mkdir(parents=True, exist_ok=True)
    step, loss_value = 0, float("nan")
    bar = tqdm(total=cfg.epochs * per_epoch, disable=not cfg.progress, file=sys.stderr)
    for epoch in range(cfg.epochs):
        order = rng.permutation(len(data))
        for i in range(per_epoch):
            idx = order[i * cfg.batch : (i + 1) * cfg.batch]
            x = _batch(data.frames[idx], data.real[idx], rng, cfg.min_length, cfg.speed)
            h0, c0 = model.initial_state(len(idx))
            logits, _, _ = model(x, h0, c0)
            loss = _loss(logits, labels[idx], weights)
            optim.zero_grad()
            loss.backward()  # type: ignore[no-untyped-call]
            nn.utils.clip_grad_norm_(model.parameters(), 1.0)
            optim.step()
            sched.step()
            step += 1
            loss_value = float(loss)
            bar.update()
            bar.set_postfix(epoch=epoch + 1, loss=f"{loss_value:.3f}")
            if cfg.max_steps is not None and step >= cfg.max_steps:
                break
        torch.save(
            {"epoch": epoch + 1, "model": model.state_dict(), "config": str(asdict(cfg))},
            ckpt_dir / f"epoch_{epoch + 1:03d}.pt",
        )
        if cfg.max_steps is not None and step >= cfg.max_steps:
            break
    bar.close()
    threshold, unknown_weight = DEFAULT_THRESHOLD, 1.0
    if validation:
        frames, vlabels = clip_windows(validation, classes, VALIDATION_FRAMES, REAL_STRIDE)
        threshold, unknown_weight, _ = choose_decision(
            _probabilities(model, frames),
            vlabels,
            _probabilities(model, hide_joints(frames, cfg.seed)),
            classes.index(UNKNOWN),
        )
    export(model, cfg.out, cfg.hidden, classes, threshold, unknown_weight)
    return {
        "out": str(cfg.out),
        "steps": step,
        "final_loss": loss_value,
        "samples": len(data),
        "real_samples": int(data.real.sum()),
        "classes": list(classes),
        "threshold": threshold,
        "unknown_weight": unknown_weight,
    }


def _probabilities(model: MultiStageLSTM, frames: np.ndarray, batch: int = 256) -> np.ndarray:
    """Stage 3's last-frame probabilities of raw windows (validation)."""
    wrapper = LastFrameProbabilities(model).eval()
    out = []
    with torch.no_grad():
        for s in range(0, len(frames), batch):
            x = torch.from_numpy(preprocess_batch(frames[s : s + batch]))
            h0, c0 = model.initial_state(len(x))
            out.append(wrapper(x, h0, c0)[0].numpy())
    return np.concatenate(out)


def export(
    model: MultiStageLSTM,
    path: Path,
    hidden: int,
    classes: tuple[str, ...] = ACTIONS,
    threshold: float = DEFAULT_THRESHOLD,
    unknown_weight: float = 1.0,
) -> None:
    """The ONNX graph (window or one frame, with states) and its metadata."""
    import onnx

    model.eval()
    wrapper = LastFrameProbabilities(model)
    x = torch.zeros(1, 8, FEATURES_PER_FRAME)
    h0, c0 = model.initial_state(1)
    path.parent.mkdir(parents=True, exist_ok=True)
    torch.onnx.export(
        wrapper,
        (x, h0, c0),
        str(path),
        dynamo=False,
        input_names=["features", "h0", "c0"],
        output_names=["probabilities", "h", "c"],
        dynamic_axes={
            "features": {0: "batch", 1: "frames"},
            "h0": {1: "batch"},
            "c0": {1: "batch"},
            "probabilities": {0: "batch"},
            "h": {1: "batch"},
            "c": {1: "batch"},
        },
        opset_version=17,
    )
    proto = onnx.load(str(path))
    meta = {
        "classes": list(classes),
        "threshold": threshold,
        "unknown_weight": unknown_weight,
        "fps": FPS,
        "hidden": hidden,
        "stages": len(model.stages),
        "features": FEATURES_PER_FRAME,
        "box_height_fraction": list(BOX_HEIGHT_RANGE),
    }
    entry = proto.metadata_props.add()
    entry.key, entry.value = METADATA_KEY, json.dumps(meta)
    onnx.save(proto, str(path))


def export_checkpoint(checkpoint: Path, out: Path) -> dict[str, object]:
    """Export a training checkpoint (e.g. an interrupted run's last epoch) to ONNX."""
    state = torch.load(checkpoint, map_location="cpu", weights_only=True)["model"]
    hidden = int(state["stages.0.lstm.weight_hh_l0"].shape[1])
    outputs = int(state["stages.0.head.weight"].shape[0])
    stages = len({key.split(".")[1] for key in state if key.startswith("stages.")})
    classes = ACTIONS if outputs == len(ACTIONS) else (*ACTIONS, UNKNOWN)
    model = MultiStageLSTM(FEATURES_PER_FRAME, len(classes), hidden, stages)
    model.load_state_dict(state)
    export(model, out, hidden, classes)
    return {"out": str(out), "checkpoint": str(checkpoint), "hidden": hidden}
