"""The open set: an ``unknown`` outcome, a validated threshold, clip scores and fall alerts."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from amiro.activity.dataset import subject_body, window
from amiro.activity.labels import ACTIONS, NTU_ACTION_IDS, UNKNOWN
from amiro.activity.ntu import Body, SkeletonSequence, write_skeleton_file
from amiro.activity.onnx_model import ActivityModel
from amiro.activity.open_set import choose_decision, clip_windows
from amiro.activity.real_sets import Clip
from amiro.activity.recognizer import SkeletonActivityRecognizer
from amiro.activity.skeleton import J
from amiro.cli import main
from amiro.evaluation.activity_real import fall_alerts, open_set_scores, stitch, windows

CLASSES = (*ACTIONS, UNKNOWN)


def _clip(label: str | None, frames: int) -> Clip:
    return Clip("kard", 1, 1, label, np.zeros((frames, 25, 3)))


def test_other_actions_train_the_unknown_outcome_and_short_clips_are_padded() -> None:
    frames, labels = clip_windows(
        [_clip("drink_water", 50), _clip(None, 12)], CLASSES, length=40, stride=10
    )
    assert frames.shape == (3, 40, 25, 3)
    assert labels.tolist() == [0, 0, CLASSES.index(UNKNOWN)]


def test_the_threshold_balances_known_accuracy_and_unknown_rejection() -> None:
    unknown = CLASSES.index(UNKNOWN)
    probs = np.full((4, len(CLASSES)), 0.01)
    probs[0, 0] = probs[1, 1] = 0.9  # confident and right
    probs[2, 0] = probs[3, 2] = 0.55  # unsure guesses on other actions
    labels = np.array([0, 1, unknown, unknown])
    floor, weight, _ = choose_decision(probs, labels, probs, unknown)
    assert 0.55 < floor <= 0.9 and weight == 1.0


def test_a_hidden_body_is_not_taken_for_something_else() -> None:
    """With joints hidden the model leans to ``unknown`` on known actions: the validated
    rule weighs ``unknown`` down only as far as the unknown windows stay rejected."""
    unknown = CLASSES.index(UNKNOWN)
    probs = np.full((4, len(CLASSES)), 0.01)
    probs[0, 0] = probs[1, 1] = 0.9
    probs[2, unknown] = probs[3, unknown] = 0.9
    hidden = probs.copy()
    hidden[0, 0], hidden[0, unknown] = 0.45, 0.5  # known, hidden joints: unsure, "unknown"
    labels = np.array([0, 1, unknown, unknown])
    floor, weight, score = choose_decision(probs, labels, hidden, unknown)
    assert weight < 0.9 and floor <= 0.45 and score == 1.0
    assert choose_decision(probs, labels, probs, unknown)[1] == 1.0


def test_unknown_or_unsure_is_no_activity(tiny_open_set_model: ActivityModel) -> None:
    model = tiny_open_set_model
    assert model.outcomes == CLASSES and model.classes == ACTIONS
    assert 0.3 <= model.info.threshold <= 0.95
    probs = np.zeros(len(CLASSES))
    probs[CLASSES.index(UNKNOWN)] = 0.99
    assert model.decide(probs) == (None, pytest.approx(0.99))
    probs = np.zeros(len(CLASSES))
    probs[0] = 0.99
    assert model.decide(probs)[0] == ACTIONS[0]
    assert model.decide(probs, threshold=0.995)[0] is None


class _Source:
    def __init__(self, frames: np.ndarray) -> None:
        self.frames = frames

    def window(self, person: str, frames: int) -> np.ndarray:
        return self.frames[-frames:]

    def framing(self, person: str) -> tuple[float, bool]:
        return (0.6, False)


class _SaysUnknown(ActivityModel):
    def classify(self, frames: np.ndarray) -> np.ndarray:
        probs = np.zeros(len(self.outcomes))
        probs[self.outcomes.index(UNKNOWN)] = 1.0
        return probs


def test_the_recogniser_reports_unknown_as_no_activity(
    tiny_open_set_model: ActivityModel,
) -> None:
    model = _SaysUnknown(tiny_open_set_model.path)
    frames = window("drink_water", subject_body(0, 0), 0.0, np.random.default_rng(0))
    reading = SkeletonActivityRecognizer(_Source(frames), model).observe("maria")
    assert reading.skeleton_complete and reading.label is None


def test_open_set_scores_count_clips_and_keep_an_unknown_row_and_column() -> None:
    truth = ["drink_water", "drink_water", None, None, None]
    said = ["drink_water", None, None, "typing", None]
    scores = open_set_scores(truth, said)
    assert scores["known_accuracy"] == 0.5 and scores["unknown_rejection"] == pytest.approx(
        2 / 3, abs=1e-3
    )
    labels, matrix = scores["confusion"]["labels"], np.array(scores["confusion"]["matrix"])
    assert labels[-1] == UNKNOWN and matrix.shape == (len(CLASSES), len(CLASSES))
    assert matrix[-1, -1] == 2 and matrix[-1, ACTIONS.index("typing")] == 1


def test_two_falling_readings_in_a_row_raise_one_alert_and_rearm() -> None:
    assert fall_alerts([True, False, True, True, True, True, True]) == [3, 5]


def test_stitched_clips_continue_where_the_last_left_the_person() -> None:
    a = np.zeros((10, 25, 3))
    b = np.ones((10, 25, 3)) * np.array([5.0, 0.2, 3.0])
    out = stitch([a, b], transition_s=1.0)
    assert len(out) == 35  # 15 frames (1 s) of transition between the two
    np.testing.assert_allclose(out[-10, J["SpineBase"]], [0.0, 0.2, 0.0])
    step = np.abs(np.diff(out[:, J["Head"]], axis=0)).max()
    assert step <= 0.2 / 15  # no jump: the height changes over the transition
    assert len(windows(out)) == 1  # 2 s windows every 0.5 s: 35 frames hold one


def test_evaluate_on_ntu_files_of_any_action_gives_the_open_set_contract_keys(
    capsys: pytest.CaptureFixture[str], tmp_path: Path, tiny_model: ActivityModel
) -> None:
    rng = np.random.default_rng(2)
    for subject, action_id in ((1, NTU_ACTION_IDS["drink_water"]), (2, 99), (3, 12)):
        joints = window("drink_water", subject_body(subject, 0), 0.0, rng, 40)
        name = f"S001C001P{subject:03d}R001A{action_id:03d}.skeleton"
        write_skeleton_file(
            tmp_path / name, SkeletonSequence(40, [Body("1", joints, np.ones(40, bool))])
        )
    code = main(
        ["har", "evaluate", "--ntu", str(tmp_path), "--model", str(tiny_model.path), "--json"]
    )
    report = json.loads(capsys.readouterr().out)
    assert code == 0 and report["files"] == 3
    assert report["known_files"] == 1 and report["unknown_files"] == 2
    for key in ("known_accuracy", "unknown_rejection", "fall_alerts_per_hour"):
        assert report[key] >= 0.0
    assert report["confusion"]["labels"][-1] == UNKNOWN
    assert sum(map(sum, report["confusion"]["matrix"])) == 3


def test_a_rewritten_decision_rule_changes_the_decisions_not_the_network(
    tiny_open_set_model: ActivityModel, tmp_path: Path
) -> None:
    from amiro.activity.calibrate import write_decision

    out = tmp_path / "calibrated.onnx"
    write_decision(tiny_open_set_model.path, out, 0.35, 0.5)
    model = ActivityModel(out)
    assert (model.info.threshold, model.info.unknown_weight) == (0.35, 0.5)
    window = np.random.default_rng(0).normal(0.0, 0.3, (30, 25, 3)) + np.array([0.0, 1.0, 3.0])
    np.testing.assert_allclose(model.classify(window), tiny_open_set_model.classify(window))
    probs = np.zeros(len(CLASSES))
    probs[CLASSES.index(UNKNOWN)], probs[0] = 0.5, 0.4  # unknown, unless weighed down
    assert tiny_open_set_model.decide(probs, threshold=0.35)[0] is None
    assert model.decide(probs) == (ACTIONS[0], pytest.approx(0.4))
