"""The hydration scenario with the dialogue stack's NLU (not the oracle) in the loop."""

from __future__ import annotations

import pytest

from amiro.dialogue.audio_loop import AudioLoopUnderstanding
from amiro.dialogue.config import AsrConfig, DialogueConfig
from amiro.dialogue.understanding import Nlu
from amiro.scenarios.hydration import HydrationOptions, scenario_config
from amiro.scenarios.recorder import EventRecorder
from amiro.system import System, build_system


def _run(lang: str, cfg: DialogueConfig, branch: str | None = None) -> tuple[System, str]:
    scenario = scenario_config(HydrationOptions(lang=lang, branch=branch))
    system = build_system(scenario.model_copy(update={"dialogue": cfg}))
    dialogue = system.dialogue
    recorder = EventRecorder(system.runtime)

    def finished() -> bool:
        runs = [r for r in system.engine.runs.values() if r.name == "hydration"]
        return bool(runs) and runs[0].done

    system.start()
    system.runtime.spin_until(finished, 900.0)
    system.stop()
    run = next(r for r in system.engine.runs.values() if r.name == "hydration")
    assert isinstance(dialogue.nlu, Nlu | AudioLoopUnderstanding)
    heard = [e for e in recorder.events if e.get("type") == "heard"]
    assert heard, f"Listen heard nothing ({run.outcome})"
    return system, run.outcome


@pytest.mark.slow
@pytest.mark.parametrize("lang", ["en", "ro", "fr"])
def test_hydration_completes_with_the_nlu(lang: str) -> None:
    _, outcome = _run(lang, DialogueConfig())
    assert outcome == "completed"


@pytest.mark.slow
def test_hydration_postpone_branch_with_the_nlu() -> None:
    _, outcome = _run("fr", DialogueConfig(), branch="no_confirmation")
    assert outcome != "timeout"


@pytest.mark.slow
def test_hydration_in_english_through_pocketsphinx() -> None:
    system, outcome = _run("en", DialogueConfig(asr=AsrConfig(backend="pocketsphinx")))
    assert outcome == "completed"
    loop = system.engine.modules.nlu
    assert isinstance(loop, AudioLoopUnderstanding)
    assert loop.heard and all(recognised for _, recognised in loop.heard)
