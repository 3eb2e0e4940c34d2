"""``build_dialogue``: the dialogue stack from its configuration, for ``system.py``."""

from __future__ import annotations

import logging
from collections.abc import Iterable
from dataclasses import dataclass

from amiro.core.clock import Clock
from amiro.core.config import ConfigError
from amiro.core.registry import create, resolve
from amiro.core.runtime import Runtime
from amiro.dialogue.actions import Actions, Submit
from amiro.dialogue.asr import ConfidenceGate, Recognizer
from amiro.dialogue.audio_loop import AudioLoopUnderstanding
from amiro.dialogue.config import DialogueConfig
from amiro.dialogue.domain import load_dm
from amiro.dialogue.manager import DialogueManager
from amiro.dialogue.microphone import SimMicrophone
from amiro.dialogue.node import DialogueNode, TtsNode
from amiro.dialogue.oracle import OracleUnderstanding
from amiro.dialogue.output import BusSpeechOutput
from amiro.dialogue.ports import SpeechOutput, Understanding
from amiro.dialogue.profiles import SpeakerProfile
from amiro.dialogue.recognizer_node import RecognizerNode
from amiro.dialogue.sources import Sources, offline_sources
from amiro.dialogue.tts import Synthesizer
from amiro.dialogue.understanding import Nlu
from amiro.dialogue.voicing import Voicer

log = logging.getLogger(__name__)


@dataclass
class Dialogue:
    speech: SpeechOutput
    nlu: Understanding
    manager: DialogueManager
    node: DialogueNode
    tts: TtsNode | None = None

    @property
    def hearing(self) -> str:
        """``audio`` when the residents' replies are voiced and recognised, else
        ``text-oracle`` (chosen, or the speech stack missing): a report says which."""
        return "audio" if isinstance(self.nlu, AudioLoopUnderstanding) else "text-oracle"


def make_synthesizer(cfg: DialogueConfig) -> Synthesizer:
    """The TTS engine ``tts.backend`` names (:mod:`amiro.dialogue.backends`)."""
    synthesizer: Synthesizer = create("tts", cfg.tts.backend, cfg.tts)
    return synthesizer


def make_recognizer(
    cfg: DialogueConfig, grammar: str | None = None, lang: str = "en", names: Iterable[str] = ()
) -> Recognizer:
    """The recogniser ``asr.backend`` names, its results gated by the configured confidence
    threshold (the Listen one for the ``answers`` grammar); ``names`` (the household's) join
    the configured vocabulary."""
    grammar = grammar or cfg.asr.grammar
    asr = cfg.asr
    if names:
        asr = asr.model_copy(update={"vocabulary": [*asr.vocabulary, *names]})
    recognizer: Recognizer = create("asr", asr.backend, asr, grammar, lang)
    answers = grammar == "answers"
    return ConfidenceGate(recognizer, cfg.asr.listen_threshold if answers else cfg.asr.reject_below)


def text_hearing(cfg: DialogueConfig) -> DialogueConfig:
    """The configuration with the text oracle for the simulated replies a process reads as
    text: a split deployment's understanding answers a service call of a few seconds
    (``amiro deploy``), too short for voicing and recognising a reply on a loaded 2-core
    machine, so a split deployment hears audio through its microphone topic instead
    (``hear_audio``: :func:`add_microphone`, :func:`add_recognizer`)."""
    return cfg.model_copy(update={"hearing": "text-oracle"})


def build_understanding(
    cfg: DialogueConfig, profiles: dict[str, SpeakerProfile], clock: Clock | None = None
) -> tuple[Nlu, Understanding]:
    """The household's NLU (relative days dated on ``clock``), and what Listen tasks
    understand replies with: the NLU behind simulated audio and the ASR (``hearing: audio``),
    on the heard text (``text-oracle``), or the oracle intent labels when configured
    (``nlu: oracle``)."""
    training = {str(k): v for k, v in cfg.training_data.items()}
    nlu = Nlu(cfg.nlu_threshold, training, profiles, clock)
    nlu.warm_up()
    understanding: Understanding = create("nlu", cfg.nlu, nlu, cfg, profiles)
    return nlu, understanding


def amiro_understanding(
    nlu: Nlu, cfg: DialogueConfig, profiles: dict[str, SpeakerProfile]
) -> Understanding:
    """The household's NLU behind simulated audio and the ASR, or on the heard text (the
    text oracle, chosen or, said once, when the speech stack is not installed)."""
    if cfg.hearing == "text-oracle":
        return nlu
    try:
        resolve("asr", cfg.asr.backend)  # the speech extra, or a one-line ConfigError
        synthesizer = make_synthesizer(cfg)
    except ConfigError as exc:
        log.warning("hearing: text oracle, not audio (%s)", exc)
        return nlu
    names = sorted(profiles)

    def recognizer_for(lang: str) -> Recognizer:
        return make_recognizer(cfg, "answers", lang, names)

    voicer = Voicer(synthesizer, profiles)
    return AudioLoopUnderstanding(nlu, voicer, recognizer_for, household_langs(profiles))


def household_langs(profiles: dict[str, SpeakerProfile]) -> list[str]:
    """The household's languages, the first person's first (what the robot starts in)."""
    return list(dict.fromkeys(p.lang for p in profiles.values())) or ["en"]


def add_microphone(
    runtime: Runtime, cfg: DialogueConfig, profiles: dict[str, SpeakerProfile]
) -> SimMicrophone:
    """The simulated residents' replies voiced onto ``/amiro/audio``."""
    voicer = Voicer(make_synthesizer(cfg), {**cfg.profiles, **profiles})
    return runtime.add(SimMicrophone(voicer))


def add_recognizer(
    runtime: Runtime,
    cfg: DialogueConfig,
    profiles: dict[str, SpeakerProfile],
    wait: bool = False,
) -> RecognizerNode:
    """The recogniser of ``/amiro/audio`` in the household's languages (the ``asr`` backend,
    loaded now); a one-line ConfigError without the speech extra."""
    profiles = {**cfg.profiles, **profiles}
    people = sorted(profiles)
    langs = household_langs(profiles)

    def recognizer_for(lang: str, grammar: str) -> Recognizer:
        return make_recognizer(cfg, grammar, lang, people)

    return runtime.add(RecognizerNode(recognizer_for, langs, langs[0], wait))


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
