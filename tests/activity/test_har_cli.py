"""``amiro har``: JSON on success, exit 2 and one line on stderr for bad input."""

import json
from pathlib import Path

import numpy as np
import pytest

from amiro.activity.dataset import subject_body, window
from amiro.activity.labels import ACTIONS, NTU_ACTION_IDS
from amiro.activity.ntu import Body, SkeletonSequence, write_skeleton_file
from amiro.activity.onnx_model import ActivityModel
from amiro.cli import main


def _run(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str, str]:
    code = main(["har", *args])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize(
    "args",
    [
        ["read", "missing.skeleton"],
        ["evaluate", "--model", "missing.onnx"],
        ["bench", "--iterations", "0"],
        ["train", "--out", "x.onnx", "--epochs", "0"],
        ["export", "missing.pt", "--out", "x.onnx"],
    ],
)
def test_bad_input_exits_2_with_one_line(
    capsys: pytest.CaptureFixture[str], tmp_path: Path, args: list[str]
) -> None:
    code, out, err = _run(capsys, *[str(tmp_path / a) if "." in a else a for a in args])
    assert code == 2 and out == ""
    assert err.startswith("amiro: error: ") and err.count("\n") == 1


def test_no_subcommand_prints_help_and_exits_2(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = _run(capsys)
    assert code == 2 and "evaluate" in out


def test_read_prints_the_contract_keys(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    joints = window("hand_waving", subject_body(0, 0), 0.0, np.random.default_rng(0), 6)
    path = tmp_path / "S001C001P001R001A023.skeleton"
    write_skeleton_file(path, SkeletonSequence(6, [Body("42", joints, np.ones(6, bool))]))
    code, out, _ = _run(capsys, "read", str(path), "--json")
    assert code == 0
    assert json.loads(out) == {"frames": 6, "bodies": [{"id": "42", "frames": 6}], "joints": 25}


def test_evaluate_on_ntu_files_and_bench_give_the_contract_keys(
    capsys: pytest.CaptureFixture[str], tmp_path: Path, tiny_model: ActivityModel
) -> None:
    rng = np.random.default_rng(1)
    for camera, subject in ((1, 1), (2, 3)):  # P003 is an NTU cross-subject test performer
        for action in ACTIONS[:3]:
            joints = window(action, subject_body(subject, 0), 0.0, rng, 40)
            name = f"S001C{camera:03d}P{subject:03d}R001A{NTU_ACTION_IDS[action]:03d}.skeleton"
            seq = SkeletonSequence(40, [Body("1", joints, np.ones(40, bool))])
            write_skeleton_file(tmp_path / name, seq)
    (tmp_path / "S001C001P001R001A099.skeleton").write_text("not read: not one of ours")
    model = str(tiny_model.path)
    code, out, _ = _run(capsys, "evaluate", "--ntu", str(tmp_path), "--model", model, "--json")
    report = json.loads(out)
    assert code == 0 and report["files"] == 6
    assert {"cross_subject", "cross_view", "confusion", "missing_joints"} <= set(report)
    assert sum(map(sum, report["confusion"]["matrix"])) == 6
    plots = tmp_path / "plots"
    code, out, _ = _run(
        capsys, "evaluate", "--ntu", str(tmp_path), "--model", model, "--out", str(plots)
    )
    assert code == 0 and f"confusion plot: {plots / 'har_confusion.png'}" in out
    assert (plots / "har_confusion.png").stat().st_size > 10_000
    empty = tmp_path / "empty"
    empty.mkdir()
    assert _run(capsys, "evaluate", "--ntu", str(empty), "--model", model)[0] == 2
    code, out, _ = _run(
        capsys, "bench", "--model", model, "--iterations", "1", "--repeats", "1", "--json"
    )
    report = json.loads(out)
    assert code == 0 and set(report["lengths"]) == {"5", "10", "15", "20", "25", "30", "60"}
    assert report["stream_ms_per_frame"] > 0
    assert report["pose_ms_per_frame"] > 0 and report["pose_detect_ms_per_frame"] > 0
