"""The activity model on real people: open-set accuracy per clip and false fall alerts.

A clip's decision is the most frequent outcome of its 2 s windows (every 0.5 s, the way
the robot looks): one of amiro's activities or None (the model said ``unknown`` or was
not sure).  ``known_accuracy`` is the share of clips of amiro's activities given their
class, ``unknown_rejection`` the share of clips of any other action given None.  False fall
alerts replay the fall monitor (a reading every 0.5 s, two "falling" in a row raise an
alert, re-armed at once) over the clips stitched into one continuous stream.
"""

from __future__ import annotations

import sys
from collections import Counter
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from amiro.activity.fall import FALL_LABEL
from amiro.activity.labels import ACTIONS, UNKNOWN
from amiro.activity.motion import FPS
from amiro.activity.onnx_model import ActivityModel
from amiro.activity.posture import FallLatch, confirm_fall
from amiro.activity.real_sets import Clip, role
from amiro.activity.skeleton import FloatArray, J

WINDOW_FRAMES = 30  # 2 s at 15 Hz: what the recogniser classifies
PERIOD_S = 0.5  # the fall monitor's and the decision windows' spacing
CONFIRMATIONS = 2
SECONDS_PER_HOUR = 3600.0
TRANSITION_S = 1.0  # between two stitched clips
# One labelled window: (true label or None, frames).
Decide = Callable[[np.ndarray], list[str | None]]


def windows(frames: FloatArray, length: int = WINDOW_FRAMES) -> np.ndarray:
    """The 2 s windows ending every 0.5 s (a short clip: once, its first frame repeated
    before it, as if the person had stood still)."""
    if len(frames) < length:
        frames = np.concatenate([np.repeat(frames[:1], length - len(frames), axis=0), frames])
    step = PERIOD_S * FPS
    ends = np.unique(np.round(np.arange(length, len(frames) + 1e-9, step)).astype(int))
    return np.stack([frames[e - length : e] for e in ends])


def decider(model: ActivityModel, batch: int = 512) -> Decide:
    """The recogniser's decisions for a stack of windows, in batches: the model's
    outcome, "falling" only for a body ending flat (:func:`confirm_fall`)."""

    def decide(stack: np.ndarray) -> list[str | None]:
        out: list[str | None] = []
        for s in range(0, len(stack), batch):
            part = stack[s : s + batch]
            probs = model.classify_batch(part)
            out.extend(
                confirm_fall(model.decide(p)[0], w) for p, w in zip(probs, part, strict=True)
            )
        return out

    return decide


def clip_outcomes(decide: Decide, clips: Sequence[Clip]) -> list[str | None]:
    """Each clip's decision: the most frequent outcome of its windows."""
    return clip_outcomes_of(decide, [c.frames for c in clips])


def clip_outcomes_of(decide: Decide, sequences: Sequence[FloatArray]) -> list[str | None]:
    """:func:`clip_outcomes` of bare frame sequences."""
    stacks = [windows(f) for f in sequences]
    flat = decide(np.concatenate(stacks)) if stacks else []
    out, start = [], 0
    for s in stacks:
        counts = Counter(flat[start : start + len(s)])
        out.append(counts.most_common(1)[0][0])
        start += len(s)
    return out


def open_set_scores(truth: Sequence[str | None], predicted: Sequence[str | None]) -> dict[str, Any]:
    """known_accuracy, unknown_rejection and the confusion with an ``unknown`` row/column."""
    labels = [*ACTIONS, UNKNOWN]
    index = {name: i for i, name in enumerate(labels)}
    matrix = np.zeros((len(labels), len(labels)), dtype=np.int64)
    for t, p in zip(truth, predicted, strict=True):
        matrix[index[t or UNKNOWN], index[p or UNKNOWN]] += 1
    known = [t is not None for t in truth]
    hits = [t == p for t, p in zip(truth, predicted, strict=True)]
    n_known, n_unknown = sum(known), len(known) - sum(known)
    per_class = {
        name: round(float(matrix[i, i] / matrix[i].sum()), 4)
        for i, name in enumerate(labels)
        if matrix[i].sum()
    }
    return {
        "files": len(truth),
        "known_files": n_known,
        "known_accuracy": round(sum(h for h, k in zip(hits, known, strict=True) if k) / n_known, 4)
        if n_known
        else None,
        "unknown_files": n_unknown,
        "unknown_rejection": round(
            sum(p is None for t, p in zip(truth, predicted, strict=True) if t is None) / n_unknown,
            4,
        )
        if n_unknown
        else None,
        "per_class": per_class,
        "confusion": {"labels": labels, "matrix": matrix.tolist()},
    }


def stitch(parts: Sequence[FloatArray], transition_s: float = TRANSITION_S) -> FloatArray:
    """One continuous stream: each part moved along the floor so the person starts where
    the last part left them, and ``transition_s`` of plain interpolation between the two
    poses (a person goes from one activity to the next; a cut would be a teleport no
    fall detector should be asked about)."""
    out: list[FloatArray] = []
    steps = round(transition_s * FPS)
    for part in parts:
        if out and len(part):
            last = out[-1][-1]
            shift = np.nan_to_num(last[J["SpineBase"]] - part[0, J["SpineBase"]])
            shift[1] = 0.0  # heights stay: the floor is the floor
            part = part + shift
            share = (np.arange(1, steps + 1) / (steps + 1))[:, None, None]
            out.append(last + share * (part[0] - last))
        out.append(part)
    return np.concatenate(out) if out else np.zeros((0, 25, 3))


def fall_alerts(is_fall: Sequence[bool]) -> list[int]:
    """The readings (one every 0.5 s) at which the monitor raises an alert."""
    alerts, streak = [], 0
    for i, fall in enumerate(is_fall):
        streak = streak + 1 if fall else 0
        if streak >= CONFIRMATIONS:
            alerts.append(i)
            streak = 0
    return alerts


def stream_falls(decide: Decide, stream: FloatArray) -> list[bool]:
    """Whether each 0.5 s reading of a stream says falling, as the recogniser's
    :class:`FallLatch` carries a confirmed fall while the body stays down."""
    if len(stream) == 0:
        return []
    stack = windows(stream)
    latch = FallLatch()
    return [
        latch("", label, w) == FALL_LABEL for label, w in zip(decide(stack), stack, strict=True)
    ]


def fall_alerts_per_hour(
    decide: Decide, streams: Sequence[FloatArray], progress: bool = False
) -> dict[str, float]:
    """False alerts per hour over streams in which nobody falls."""
    alerts, frames = 0, 0
    for i, stream in enumerate(streams):
        if progress:
            print(f"fall monitor over stream {i + 1}/{len(streams)}", file=sys.stderr)
        alerts += len(fall_alerts(stream_falls(decide, stream)))
        frames += len(stream)
    hours = frames / FPS / SECONDS_PER_HOUR
    return {
        "alerts": alerts,
        "hours": round(hours, 3),
        "per_hour": round(alerts / hours, 3) if hours else float("nan"),
    }


def real_streams(clips: Sequence[Clip]) -> list[FloatArray]:
    """One stream per set and subject, the subject's clips in their order."""
    groups: dict[tuple[str, int], list[FloatArray]] = {}
    for c in clips:
        groups.setdefault((c.dataset, c.subject), []).append(c.frames)
    return [stitch(parts) for _, parts in sorted(groups.items())]


PROTOCOLS = {
    "kard": "cross-subject (KARD subjects 8-10)",
    "cad60": "cross-subject (CAD-60 person 4)",
    "citi": "cross-subject (CITI subjects 8-10)",
    "florence3d": "cross-dataset (Florence 3D, never trained on)",
}


def evaluate_real(
    model: ActivityModel,
    clips: Sequence[Clip],
    held_out_only: bool = True,
    progress: bool = False,
    scored: str = "test",
) -> dict[str, Any]:
    """Per set: the open-set scores of its held-out clips (``scored``: the test subjects,
    or the validation ones to choose between models; every clip for a model that never
    saw real data) and the false fall alerts on them stitched into streams."""
    decide = decider(model)
    report: dict[str, Any] = {
        "data": "real",
        "held_out_only": held_out_only,
        "scored": scored if held_out_only else "all",
        "sets": {},
    }
    tested = [c for c in clips if not held_out_only or role(c) == scored]
    for name in sorted({c.dataset for c in tested}):
        part = [c for c in tested if c.dataset == name]
        if progress:
            print(f"scoring {len(part)} {name} clips", file=sys.stderr)
        scores = open_set_scores([c.label for c in part], clip_outcomes(decide, part))
        if not held_out_only:
            scores["protocol"] = f"all of {name}"
        elif scored == "test":
            scores["protocol"] = PROTOCOLS[name]
        else:
            scores["protocol"] = f"validation subjects of {name} (for choosing a model)"
        report["sets"][name] = scores
    report["fall_alerts"] = fall_alerts_per_hour(decide, real_streams(tested), progress)
    return report


def reading_times(frames: int, length: int = WINDOW_FRAMES) -> FloatArray:
    """When (s from the stream's start) each reading of :func:`windows` is taken."""
    if frames < length:
        return np.array([frames / FPS])
    step = PERIOD_S * FPS
    ends = np.unique(np.round(np.arange(length, frames + 1e-9, step)).astype(int))
    out: FloatArray = ends / FPS
    return out


def simulated_falls(
    decide: Decide, count: int = 48, seed: int = 3000, within_s: float = 2.0
) -> dict[str, float]:
    """Share of synthetic falls (held-out subjects, random views, the camera pitched down
    up to 20 deg, sensor noise) alerted within ``within_s`` of the pelvis starting to drop."""
    from amiro.activity.dataset import TEST_SUBJECTS, subject_body
    from amiro.activity.labels import IDLE
    from amiro.activity.motion import View, perform, sensor_noise, to_camera

    rng = np.random.default_rng(seed)
    delays = []
    for k in range(count):
        body = subject_body(TEST_SUBJECTS[k % len(TEST_SUBJECTS)], seed)
        before = np.concatenate([perform(IDLE, body, rng, sitting=False) for _ in range(2)])
        fall = perform("falling", body, rng)
        lying = np.repeat(fall[-1:], int(3 * FPS), axis=0)
        stream = np.concatenate([before, fall, lying])
        pelvis = stream[:, J["SpineBase"], 1]
        onset = len(before) + int(np.argmax(pelvis[len(before) :] < pelvis[0] - 0.03))
        view = View(
            yaw=rng.uniform(-np.pi, np.pi),
            distance=rng.uniform(2.0, 4.0),
            height=rng.uniform(0.8, 1.3),
            pitch=rng.uniform(0.0, 0.35),
        )
        seen = sensor_noise(to_camera(stream, view), rng)
        times = reading_times(len(seen))
        alerts = [times[i] - onset / FPS for i in fall_alerts(stream_falls(decide, seen))]
        after = [d for d in alerts if d >= 0.0]
        delays.append(min(after) if after else np.inf)
    hits = [d for d in delays if d <= within_s]
    return {
        "falls": count,
        "detected_within_s": within_s,
        "detected": round(len(hits) / count, 4),
        "median_delay_s": round(float(np.median(hits)), 3) if hits else float("nan"),
    }
