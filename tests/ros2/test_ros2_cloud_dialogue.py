"""Dialogue in the cloud: the edge's Listen understands answers through a service that the
cloud's dialogue stack answers, over ROS 2, with sim, edge and cloud as three OS processes."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

import pytest

from amiro.core import names
from amiro.core.clock import SimClock
from amiro.core.messages import SpeechHeard
from amiro.core.runtime import Runtime
from amiro.deploy.dialogue import RemoteUnderstanding, UnderstandingService
from amiro.deploy.launch import Launcher, load_deployment
from amiro.dialogue.oracle import OracleUnderstanding

DEPLOYMENT = Path(
    str(resources.files("amiro").joinpath("data/deployments/hydration-dialogue-cloud.yaml"))
)


def test_remote_understanding_answers_through_the_bus_service() -> None:
    runtime = Runtime(SimClock())
    service = runtime.add(UnderstandingService(OracleUnderstanding()))
    runtime.start()
    heard = SpeechHeard(text="later", lang="en", speaker="maria", intent="postpone", confidence=0.7)
    assert RemoteUnderstanding(runtime.bus).intent(heard) == ("postpone", 0.7)
    assert [u.intent for u in service.answered] == ["postpone"]


def test_remote_understanding_without_a_server_reads_as_not_understood() -> None:
    runtime = Runtime(SimClock())
    runtime.start()
    heard = SpeechHeard(text="yes", lang="en", speaker="maria", intent="affirm", confidence=0.9)
    assert not runtime.bus.has_service(names.UNDERSTAND)
    assert RemoteUnderstanding(runtime.bus).intent(heard) == ("out_of_scope", 0.0)


@pytest.mark.slow
def test_listen_understands_in_the_cloud_and_hydration_completes(
    tmp_path: Path, domain_id: int
) -> None:
    launcher = Launcher(load_deployment(DEPLOYMENT), tmp_path, domain_id=domain_id)
    outcome = launcher.run_all()
    assert outcome == "cloud finished"
    edge = launcher.report("edge")
    cloud = launcher.report("cloud")
    served = cloud["services"][f"ros2_serve:{names.UNDERSTAND}"]
    called = edge["services"][f"ros2_call:{names.UNDERSTAND}"]
    assert served["received"] >= 1 and served["sent"] == served["received"]
    assert called["sent"] == called["received"] >= 1
    assert served["errors"] == 0 and called["errors"] == 0
    # Listen's intent and confidence are the ones the cloud's NLU gave.
    listened = [
        e["detail"]
        for e in edge["events"]
        if e["type"] == "task_finished" and e["task"] == "listen"
    ]
    assert listened and cloud["understood"]
    assert listened[-1]["intent"] == cloud["understood"][-1]["intent"] == "affirm"
    assert round(listened[-1]["confidence"], 3) == cloud["understood"][-1]["confidence"]
    assert edge["runs"] and edge["runs"][0]["outcome"] == "completed"  # later ones may run on
    assert cloud["outcome"] == "acknowledged" and cloud["pending_notifications"] == []
    assert all(c["exit_code"] is not None for c in launcher.summary())
    assert not launcher.unclean_exits(), launcher.unclean_exits()


HEARING = Path(
    str(resources.files("amiro").joinpath("data/deployments/hydration-hearing-cloud.yaml"))
)


@pytest.mark.slow
def test_the_cloud_hears_the_residents_audio_and_listen_reads_its_transcripts(
    tmp_path: Path, domain_id: int
) -> None:
    launcher = Launcher(load_deployment(HEARING), tmp_path, domain_id=domain_id)
    assert launcher.run_all() == "cloud finished"
    sim, edge, cloud = (launcher.report(p) for p in ("sim", "edge", "cloud"))
    # every reply went out as audio, and was heard by the cloud's recogniser in English
    recognized = cloud["recognized"]
    assert len(sim["voiced"]) == sim["replies"] == len(recognized) >= 1
    assert all(r["lang"] == "en" and r["text"] and r["speech_s"] > 0.5 for r in recognized)
    assert all(r["published"] >= r["ended"] for r in recognized)  # not before it was said
    # what Listen heard is what the cloud recognised, and its intent the cloud NLU's answer
    heard = [e["text"] for e in edge["events"] if e["type"] == "heard"]
    assert heard == [r["text"] for r in recognized]
    answers = [
        (e["detail"]["intent"], round(e["detail"]["confidence"], 3))
        for e in edge["events"]
        if e["type"] == "task_finished" and e.get("task_type") == "Listen"
    ]
    assert answers == [(u["intent"], u["confidence"]) for u in cloud["understood"]]
    assert answers[0][0] == "affirm"  # the reminder's answer, heard in the audio
    called = edge["services"][f"ros2_call:{names.UNDERSTAND}"]
    assert called["sent"] == called["received"] == len(answers) and called["errors"] == 0
    # seen drinking, or (the watch missed it) confirmed by voice: the reminder was answered
    assert edge["runs"][0]["outcome"] in ("completed", "confirmed_by_voice")
    assert cloud["outcome"] == "acknowledged" and cloud["pending_notifications"] == []
    assert not launcher.unclean_exits(), launcher.unclean_exits()
