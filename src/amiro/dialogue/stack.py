"""``build_dialogue``: the dialogue stack from its configuration, for ``system.py``."""

from __future__ import annotations

from dataclasses import dataclass

from amiro.core.clock import Clock
from amiro.core.registry import create
from amiro.core.runtime import Runtime
from amiro.dialogue.actions import Actions, Submit
from amiro.dialogue.asr import ConfidenceGate, Recognizer
from amiro.dialogue.audio_loop import AudioLoopUnderstanding
from amiro.dialogue.config import DialogueConfig
from amiro.dialogue.domain import load_dm
from amiro.dialogue.manager import DialogueManager
from amiro.dialogue.node import DialogueNode, TtsNode
from amiro.dialogue.oracle import OracleUnderstanding
from amiro.dialogue.output import BusSpeechOutput
from amiro.dialogue.ports import SpeechOutput, Understanding
from amiro.dialogue.profiles import SpeakerProfile
from amiro.dialogue.sources import Sources, offline_sources
from amiro.dialogue.tts import Synthesizer
from amiro.dialogue.understanding import Nlu


@dataclass
class Dialogue:
    speech: SpeechOutput
    nlu: Understanding
    manager: DialogueManager
    node: DialogueNode
    tts: TtsNode | None = None


def make_synthesizer(cfg: DialogueConfig) -> Synthesizer:
    """The TTS engine ``tts.backend`` names (:mod:`amiro.dialogue.backends`)."""
    synthesizer: Synthesizer = create("tts", cfg.tts.backend, cfg.tts)
    return synthesizer


def make_recognizer(
    cfg: DialogueConfig, grammar: str | None = None, lang: str = "en"
) -> Recognizer:
    """The recogniser ``asr.backend`` names, its results gated by the configured confidence
    threshold (the Listen one for the ``answers`` grammar)."""
    grammar = grammar or cfg.asr.grammar
    recognizer: Recognizer = create("asr", cfg.asr.backend, cfg.asr, grammar, lang)
    answers = grammar == "answers"
    return ConfidenceGate(
        recognizer, cfg.asr.listen_reject_below if answers else cfg.asr.reject_below
    )


def build_understanding(
    cfg: DialogueConfig, profiles: dict[str, SpeakerProfile], clock: Clock | None = None
) -> tuple[Nlu, Understanding]:
    """The household's NLU (relative days dated on ``clock``), and what Listen tasks
    understand replies with: the NLU on the heard text, the NLU behind simulated audio and
    the ASR (``asr.sim_audio``), or the oracle when configured."""
    training = {str(k): v for k, v in cfg.training_data.items()}
    nlu = Nlu(cfg.nlu_threshold, training, profiles, clock)
    nlu.warm_up()
    understanding: Understanding = create("nlu", cfg.nlu, nlu, cfg, profiles)
    return nlu, understanding


def amiro_understanding(
    nlu: Nlu, cfg: DialogueConfig, profiles: dict[str, SpeakerProfile]
) -> Understanding:
    """The household's NLU on the heard text, or behind simulated audio and the ASR."""
    if cfg.asr.sim_audio:
        recognizer = make_recognizer(cfg, grammar="answers")
        return AudioLoopUnderstanding(nlu, make_synthesizer(cfg), recognizer, profiles)
    return nlu


def oracle_understanding(
    nlu: Nlu, cfg: DialogueConfig, profiles: dict[str, SpeakerProfile]
) -> Understanding:
    return OracleUnderstanding()


def build_dialogue(
    runtime: Runtime,
    cfg: DialogueConfig,
    profiles: dict[str, SpeakerProfile] | None = None,
    submit: Submit | None = None,
    sources: Sources | None = None,
) -> Dialogue:
    """Speech output, understanding for Listen, and the dialogue manager node (added to the
    runtime).  ``submit(kind, payload)`` hands behaviour requests (``go_to``) to the engine."""
    profiles = {**cfg.profiles, **(profiles or {})}
    nlu, understanding = build_understanding(cfg, profiles, runtime.clock)
    domain, stories = load_dm(cfg.dm)
    actions = Actions(sources or offline_sources(), submit, runtime.clock)
    manager = DialogueManager(nlu, domain, actions, stories=stories)
    node = runtime.add(DialogueNode(manager, profiles))
    tts = None
    if cfg.tts.output != "none":
        tts = runtime.add(TtsNode(make_synthesizer(cfg), profiles, cfg.tts.output, cfg.tts.wav_dir))
    speech = BusSpeechOutput(runtime.bus, cfg.words_per_second)
    return Dialogue(speech, understanding, manager, node, tts)
