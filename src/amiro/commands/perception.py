"""``amiro perception evaluate`` (the paper's section-4.2 protocol on generated RGB-D data)
and ``amiro perception bench`` (the issue's speed targets)."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING

from amiro.commands.support import (
    add_command,
    add_group,
    add_out_flag,
    emit_json,
    emit_report,
    out_file,
    show_progress,
)

if TYPE_CHECKING:
    from amiro.commands.support import Subcommands


def register(sub: Subcommands) -> None:
    commands = add_group(
        sub, "perception", "person detection and 3D positions", dest="perception_command"
    )
    ev = add_command(
        commands,
        "evaluate",
        _evaluate,
        help="Tables 7–13 of the paper on the generated RGB-D dataset",
        description="Generates the paper's dataset (17 people x 4 distances x 5 postures x 5 "
        "camera placements x 5 images) in the simulator and scores the paper's formulas, the "
        "improved estimator and the detector's counting errors.",
    )
    ev.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    ev.add_argument("--people", type=int, default=17, help="people in the dataset (default 17)")
    ev.add_argument("--images", type=int, default=5, help="images per configuration (default 5)")
    add_out_flag(ev)
    ev.add_argument("--plot", type=Path, help="PNG of the error by distance (default: in --out)")
    ev.add_argument("--no-plot", action="store_true", help="do not write the PNG")
    bench = add_command(
        commands,
        "bench",
        _bench,
        help="time of coordinate estimation per frame and of face identification per face",
        description="Coordinate estimation of a frame's detections (depth image to map "
        "positions) on generated RGB-D frames, and dlib face identification of one face on "
        "the shipped portraits; medians in ms, beside the issue's targets (1 ms, 200 ms).",
    )
    bench.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    bench.add_argument("--frames", type=int, default=200, help="frames timed (default 200)")
    bench.add_argument("--people", type=int, default=3, help="detections per frame (default 3)")
    bench.add_argument("--repeats", type=int, default=10, help="face timings (default 10)")
    camera = add_command(
        commands,
        "bench-camera",
        _bench_camera,
        help="time per 640 x 480 frame of the camera backends (HOG, ONNX detector, pose)",
        description="People from an RGB-D frame with OpenCV's HOG and with an ONNX detector, "
        "and skeletons with an ONNX pose model, on a generated 640 x 480 frame; medians in "
        "ms.  Without --model / --pose-model, random-weight stand-ins of a small YOLO's "
        "size are generated (needs the onnx package).",
    )
    camera.add_argument("--model", type=Path, help="a YOLO-layout ONNX detector")
    camera.add_argument("--pose-model", type=Path, help="a YOLO-pose-layout ONNX model")
    camera.add_argument(
        "--keypoints",
        default="coco17",
        choices=["coco17", "openpose_body25", "mediapipe_blazepose33"],
        help="the pose model's keypoint order (default coco17)",
    )
    camera.add_argument("--seed", type=int, default=1, help="stand-in weights (default 1)")
    camera.add_argument("--repeats", type=int, default=10, help="timed frames (default 10)")
    camera.add_argument(
        "--scenes", type=int, default=50, help="generated frames for the placement error"
    )


def _evaluate(args: argparse.Namespace) -> int:
    import numpy as np

    from amiro.core.config import ConfigError
    from amiro.evaluation.perception_evaluate import evaluate
    from amiro.perception.report import plot_by_distance, print_report
    from amiro.sim.rgbd_dataset import DatasetSpec

    if args.people < 1 or args.images < 1:
        raise ConfigError("--people and --images must be at least 1")
    spec = DatasetSpec(people=args.people, images=args.images)
    # the output folder first: a bad --out is an error now, not after the evaluation
    plot = None if args.no_plot else args.plot or out_file(args, "perception_error_by_distance.png")
    report = evaluate(np.random.default_rng(args.seed), spec, progress=show_progress(args))
    if plot is not None:
        report["plot"] = str(plot_by_distance(report, plot))
    if args.json:
        emit_json(report)
    else:
        print_report(report)
    return 0


def _bench(args: argparse.Namespace) -> int:
    import numpy as np

    from amiro.core.config import ConfigError
    from amiro.evaluation.perception_bench import bench

    if min(args.frames, args.people, args.repeats) < 1:
        raise ConfigError("--frames, --people and --repeats must be at least 1")
    report = bench(np.random.default_rng(args.seed), args.frames, args.people, args.repeats)
    text = (
        f"coordinate estimation: {report['estimate_ms_per_frame']} ms per frame of "
        f"{args.people} detections (target < 1 ms)\n"
        f"face identification (dlib): {report['face_ms_per_face_in_frame']} ms per face in a "
        f"640 x 480 frame, {report['face_ms_per_face_crop']} ms in a head crop (target < 200 ms)"
    )
    return emit_report(args, report, text)


def _bench_camera(args: argparse.Namespace) -> int:
    import numpy as np

    from amiro.core.config import ConfigError
    from amiro.evaluation.perception_camera_bench import bench_camera

    if args.repeats < 1 or args.scenes < 1:
        raise ConfigError("--repeats and --scenes must be at least 1")
    report = bench_camera(
        np.random.default_rng(args.seed),
        args.repeats,
        args.scenes,
        args.model,
        args.pose_model,
        args.keypoints,
    )
    mae = report["placement_mae_m"]
    text = "\n".join(
        [
            f"640 x 480 frame, median of {args.repeats}:",
            f"  people, HOG detector:  {report['hog_ms_per_frame']} ms",
            f"  people, ONNX detector: {report['onnx_ms_per_frame']} ms ({report['onnx_model']})",
            f"  skeletons, ONNX pose:  {report['pose_ms_per_frame']} ms ({report['pose_model']})",
            f"  (the activity model takes a skeleton every "
            f"{report['activity_frame_budget_ms']} ms)",
            *(
                f"placement, {name.replace('_', ' ')}: MAE x / y / z {m['x']} / {m['y']} / "
                f"{m['z']} m, placed in {m['found']} of {m['scenes']} frames"
                for name, m in mae.items()
            ),
        ]
    )
    return emit_report(args, report, text)
