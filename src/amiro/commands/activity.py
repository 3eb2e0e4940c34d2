"""``amiro har``: train, evaluate and benchmark the activity model; read NTU skeleton files."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from amiro.commands.support import add_command, add_group, emit_json, emit_report, out_dir

if TYPE_CHECKING:
    from amiro.commands.support import Subcommands


def register(sub: Subcommands) -> None:
    cmds = add_group(
        sub, "har", "human activity recognition: train, evaluate, bench, read", "har_command"
    )
    train = add_command(
        cmds,
        "train",
        _train,
        help="train the multi-stage LSTM (real skeleton sets and synthetic motion) and export "
        "ONNX (needs torch)",
    )
    train.add_argument(
        "--real",
        type=Path,
        help="folder of the real skeleton sets (kard/, florence3d/, cad60/, citi/); "
        "without it: synthetic motion only, no unknown outcome",
    )
    train.add_argument("--out", type=Path, required=True, help="the ONNX file to write")
    train.add_argument("--checkpoints", type=Path, help="folder for per-epoch checkpoints")
    train.add_argument("--epochs", type=int, default=40)
    train.add_argument("--seed", type=int, default=0)
    train.add_argument("--hidden", type=int, default=64, help="LSTM and feature width")
    train.add_argument("--per-cell", type=int, default=6, help="windows per subject/view/action")
    train.add_argument("--max-steps", type=int, help="stop after this many optimiser steps")
    train.add_argument("--stages", type=int, default=3, help="LSTM stages (the paper: 3)")

    export = add_command(
        cmds, "export", _export, help="export a training checkpoint to ONNX (needs torch)"
    )
    export.add_argument("checkpoint", type=Path)
    export.add_argument("--out", type=Path, required=True, help="the ONNX file to write")

    calibrate = add_command(
        cmds,
        "calibrate",
        _calibrate,
        help="pick a model's confidence floor and unknown weight again on the real sets' "
        "validation subjects (needs onnx)",
    )
    calibrate.add_argument("--model", type=Path, help="ONNX model (default: the shipped one)")
    calibrate.add_argument("--real", type=Path, required=True, help="the real sets' folder")
    calibrate.add_argument("--out", type=Path, required=True, help="the ONNX file to write")

    evaluate = add_command(
        cmds,
        "evaluate",
        _evaluate,
        help="accuracy: cross-subject, cross-view, confusion, missing joints",
    )
    evaluate.add_argument("--model", type=Path, help="ONNX model (default: the shipped one)")
    evaluate.add_argument("--ntu", type=Path, help="a folder of NTU RGB+D .skeleton files")
    evaluate.add_argument(
        "--real",
        type=Path,
        help="the real Kinect v1 sets' folder (kard/, florence3d/, cad60/, citi/): "
        "cross-subject and cross-dataset, open set, false fall alerts",
    )
    evaluate.add_argument(
        "--all-clips",
        action="store_true",
        help="with --real: score every clip (a model that never trained on these sets)",
    )
    evaluate.add_argument(
        "--validation",
        action="store_true",
        help="with --real: score the validation subjects instead of the test ones (to choose "
        "between trained models without looking at the test data)",
    )
    evaluate.add_argument("--seed", type=int, default=1000)
    evaluate.add_argument(
        "--out", type=Path, help="folder for the confusion plot (har_confusion.png)"
    )

    read = add_command(cmds, "read", _read, help="parse one NTU RGB+D .skeleton file")
    read.add_argument("file", type=Path)

    bench = add_command(
        cmds,
        "bench",
        _bench,
        help="inference time, preprocessing included (Table 16); pose estimation per frame",
    )
    bench.add_argument("--model", type=Path, help="ONNX model (default: the shipped one)")
    bench.add_argument("--iterations", type=int, default=200, help="calls per round")
    bench.add_argument("--repeats", type=int, default=7, help="rounds; the median is reported")


def _positive(value: int | None, name: str) -> None:
    from amiro.core.config import ConfigError

    if value is not None and value <= 0:
        raise ConfigError(f"{name} must be positive, got {value}")


def _train(args: argparse.Namespace) -> int:
    from amiro.core.config import ConfigError

    for name in ("epochs", "hidden", "per_cell", "max_steps", "stages"):
        _positive(getattr(args, name), "--" + name.replace("_", "-"))
    if args.real is not None and not args.real.is_dir():
        raise ConfigError(f"--real {args.real}: no such folder")
    try:
        from amiro.activity.train import TrainConfig, train
    except ImportError as exc:
        raise ConfigError(
            f"training needs the 'train' extra (pip install amiro[train]): {exc}"
        ) from None
    report = train(
        TrainConfig(
            out=args.out,
            epochs=args.epochs,
            hidden=args.hidden,
            seed=args.seed,
            per_cell=args.per_cell,
            max_steps=args.max_steps,
            checkpoints=args.checkpoints,
            real=args.real,
            stages=args.stages,
        )
    )
    if args.json:
        emit_json(report)
    else:
        print(f"wrote {report['out']} after {report['steps']} steps", file=sys.stderr)
    return 0


def _export(args: argparse.Namespace) -> int:
    from amiro.core.config import ConfigError

    if not args.checkpoint.is_file():
        raise ConfigError(f"{args.checkpoint}: no such file")
    try:
        from amiro.activity.train import export_checkpoint
    except ImportError as exc:
        raise ConfigError(
            f"export needs the 'train' extra (pip install amiro[train]): {exc}"
        ) from None
    report = export_checkpoint(args.checkpoint, args.out)
    if args.json:
        emit_json(report)
    return 0


def _calibrate(args: argparse.Namespace) -> int:
    from amiro.activity.calibrate import calibrate
    from amiro.core.config import ConfigError

    if not args.real.is_dir():
        raise ConfigError(f"--real {args.real}: no such folder")
    report = calibrate(args.model, args.real, args.out)
    if args.json:
        emit_json(report)
    else:
        print(
            f"wrote {report['out']}: threshold {report['threshold']}, unknown weight "
            f"{report['unknown_weight']} (validation score {report['validation_score']})"
        )
    return 0


def _evaluate(args: argparse.Namespace) -> int:
    from amiro.activity.onnx_model import ActivityModel
    from amiro.evaluation.activity_evaluate import (
        evaluate_ntu,
        evaluate_real_sets,
        evaluate_synthetic,
        format_report,
        plot_confusions,
    )

    model = ActivityModel(args.model)
    if args.ntu:
        report = evaluate_ntu(model, args.ntu)
    elif args.real:
        report = evaluate_real_sets(
            model, args.real, args.all_clips, scored="validation" if args.validation else "test"
        )
    else:
        report = evaluate_synthetic(model, args.seed)
    text = format_report(report)
    if args.out is not None:
        path = out_dir(args) / "har_confusion.png"
        plot_confusions(report, path)
        text += f"\n\nconfusion plot: {path}"
    return emit_report(args, report, text)


def _read(args: argparse.Namespace) -> int:
    from amiro.activity.ntu import read_skeleton_file

    seq = read_skeleton_file(args.file)
    report = seq.summary()
    if args.json:
        emit_json(report)
    else:
        bodies = ", ".join(f"{b['id']} ({b['frames']} frames)" for b in report["bodies"])
        print(
            f"{args.file}: {report['frames']} frames, {report['joints']} joints; bodies: {bodies}"
        )
    return 0


def _bench(args: argparse.Namespace) -> int:
    from amiro.activity.bench import pose_bench, run_bench
    from amiro.activity.onnx_model import ActivityModel

    _positive(args.iterations, "--iterations")
    _positive(args.repeats, "--repeats")
    report = run_bench(ActivityModel(args.model), args.iterations, args.repeats)
    report |= pose_bench(max(1, args.iterations // 10), min(args.repeats, 3))
    if args.json:
        emit_json(report)
    else:
        for length, ms in report["lengths"].items():
            print(f"{length:>3} frames: {ms:.3f} ms (paper: {report['paper_ms'][length]} ms)")
        print(f"streaming: {report['stream_ms_per_frame']:.3f} ms per frame")
        if report["pose_ms_per_frame"] is None:
            print(f"pose estimation: not measured ({report['pose_error']})")
        else:
            print(
                f"pose estimation ({report['pose_backend']}, {report['pose_frame']}, to NTU-25 "
                f"and lifted): {report['pose_ms_per_frame']:.1f} ms per frame tracking, "
                f"{report['pose_detect_ms_per_frame']:.1f} ms detecting every frame"
            )
    return 0
