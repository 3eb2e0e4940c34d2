"""RecognizeActivity decides from several sightings: a flickering reading of the expected
activity still confirms it, readings of no activity count neither way, and a stray
sighting among other activities does not."""

import pytest

import amiro.behavior.tasks  # noqa: F401 - registers the task types
from amiro.activity.ports import ActivityReading
from amiro.behavior.engine import BehaviorEngine, EngineConfig, GraphRun
from amiro.behavior.graph import TaskGraph
from amiro.behavior.modules import Modules
from amiro.behavior.task import check_params, make_task
from amiro.behavior.tasks.activity import RecognizeActivity
from amiro.core.clock import SimClock
from amiro.core.runtime import Runtime

D, C, U = "drink_water", "sneeze_cough", None  # U: unknown, unsure or too few joints


class Scripted:
    """Plays a fixed sequence of readings, then no activity."""

    box_range = None

    def __init__(self, labels: list[str | None]) -> None:
        self.labels = list(labels)
        self.calls = 0

    def observe(self, person: str) -> ActivityReading:
        label = self.labels[self.calls] if self.calls < len(self.labels) else None
        self.calls += 1
        return ActivityReading(label, 0.9 if label else 0.0, True)


def _watch(labels: list[str | None], **params: object) -> tuple[GraphRun, Scripted]:
    runtime = Runtime(SimClock(), seed=0)
    recognizer = Scripted(labels)
    engine = runtime.add(
        BehaviorEngine(config=EngineConfig(), modules=Modules(activity=recognizer))
    )
    runtime.start()
    task = make_task(
        "RecognizeActivity",
        {"person": "maria", "timeout_s": 15, "reframe": False, **params},
    )
    run = engine.submit(TaskGraph("watch", 1).add("rec", task))
    runtime.spin_until(lambda: run.done, 30.0)
    return run, recognizer


def test_a_flickering_drink_is_confirmed_where_a_streak_never_forms() -> None:
    run, recognizer = _watch([D, C, D, U, U, C, D])  # never two in a row
    assert run.outcome == "completed"
    assert recognizer.calls == 7  # on the third sighting among the last five labelled
    assert run.records[-1].detail["activity"] == D


def test_readings_of_no_activity_do_not_push_sightings_out() -> None:
    run, _ = _watch([D, U, U, U, U, U, U, D, U, D])
    assert run.outcome == "completed"


def test_stray_sightings_among_other_activities_are_not_enough() -> None:
    run, _ = _watch([D, C, C, C, C, D, C, C, C, C, D, C, C, C, C] * 3)
    assert run.outcome == "failed"
    detail = run.records[-1].detail
    assert detail["reason"] == "not_recognised" and detail["seen"][D] >= 5


def test_confirmations_and_window_are_parameters() -> None:
    run, recognizer = _watch([D, C, D, C, D, D], confirmations=2, of_last=2)
    assert run.outcome == "completed" and recognizer.calls == 6
    with pytest.raises(ValueError, match="of_last"):
        check_params(RecognizeActivity.Params, {"person": "p", "confirmations": 4, "of_last": 3})
