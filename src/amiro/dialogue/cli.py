"""``amiro nlu parse|evaluate``, ``amiro asr evaluate`` and ``amiro chat``."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING

from amiro.cli_support import add_command, add_group, emit_report

if TYPE_CHECKING:
    from amiro.cli_support import Subcommands

ASR_BACKENDS = ("pocketsphinx", "vosk", "google")


def register(sub: Subcommands) -> None:
    nlu = add_group(sub, "nlu", "natural-language understanding (en, ro, fr)", dest="nlu_command")
    parse = add_command(nlu, "parse", _parse, help="one utterance through the NLU")
    parse.add_argument("--lang", default="en", help="en, ro or fr (default en)")
    parse.add_argument("text", nargs="+", help="the utterance")
    ev = add_command(
        nlu, "evaluate", _evaluate_nlu, help="accuracy over labelled utterances (JSON lines)"
    )
    ev.add_argument("file", type=Path, help='JSONL: {"lang", "text", "intent", "entities"}')

    asr = add_group(sub, "asr", "speech recognition", dest="asr_command")
    aev = add_command(
        asr, "evaluate", _evaluate_asr, help="WER, sentence accuracy and RTF over WAV files"
    )
    aev.add_argument("dir", type=Path, help="WAV files named by their transcript (or .txt)")
    aev.add_argument("--lang", default="en", help="language of the recordings (default en)")
    aev.add_argument("--backend", default="pocketsphinx", help="pocketsphinx, vosk or google")
    aev.add_argument("--grammar", default="nlu", help="pocketsphinx: nlu, answers or none (LM)")
    aev.add_argument("--vosk-model", type=Path, help="Vosk model directory")

    chat = add_command(
        sub, "chat", _chat, help="talk to the dialogue module in a terminal", with_json=False
    )
    chat.add_argument("--lang", default="en", help="en, ro or fr (default en)")
    chat.add_argument("--voice", action="store_true", help="speak through the microphone")


def _parse(args: argparse.Namespace) -> int:
    from amiro.dialogue.phrases import check_language
    from amiro.dialogue.understanding import Nlu

    parsed = Nlu().parse(" ".join(args.text), check_language(args.lang))
    report = {
        "text": parsed.text,
        "lang": parsed.lang,
        "intent": {"name": parsed.intent, "confidence": round(parsed.confidence, 4)},
        "entities": parsed.entities,
        "ranking": [{"name": n, "confidence": round(c, 4)} for n, c in parsed.ranking],
    }
    ents = ", ".join(f"{k}={v}" for k, v in parsed.entities.items()) or "no entities"
    return emit_report(args, report, f"{parsed.intent} ({parsed.confidence:.2f}): {ents}")


def _evaluate_nlu(args: argparse.Namespace) -> int:
    from amiro.dialogue.nlu_eval import evaluate, read_jsonl
    from amiro.dialogue.understanding import Nlu

    nlu = Nlu()
    report = evaluate(read_jsonl(args.file), lambda lang, text: nlu.parse(text, lang))
    text = "\n".join(
        f"{lang}: n={r['n']} intent {100 * r['intent_accuracy']:.1f}% "
        f"entities {100 * r['entity_accuracy']:.1f}% {r['ms_per_utterance']:.2f} ms/utt"
        for lang, r in report.items()
    )
    return emit_report(args, report, text)


def _evaluate_asr(args: argparse.Namespace) -> int:
    from amiro.core.config import ConfigError
    from amiro.dialogue.asr_eval import evaluate_asr
    from amiro.dialogue.config import AsrConfig, DialogueConfig
    from amiro.dialogue.phrases import check_language
    from amiro.dialogue.stack import make_recognizer

    if args.backend not in ASR_BACKENDS:
        raise ConfigError(f"unknown asr backend '{args.backend}' ({', '.join(ASR_BACKENDS)})")
    asr = AsrConfig(backend=args.backend, grammar="nlu", vosk_model=args.vosk_model)
    recognizer = make_recognizer(DialogueConfig(asr=asr), args.grammar, check_language(args.lang))
    report = evaluate_asr(args.dir, recognizer)
    text = (
        f"{report['files']} files: WER {100 * report['wer']:.1f}%, sentence accuracy "
        f"{100 * report['sentence_accuracy']:.1f}%, RTF {report['rtf']:.3f}"
    )
    return emit_report(args, report, text)


def _chat(args: argparse.Namespace) -> int:
    from amiro.dialogue.chat import run_chat
    from amiro.dialogue.phrases import check_language

    return run_chat(check_language(args.lang), args.voice)
