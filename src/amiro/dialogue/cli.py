"""``amiro nlu parse|evaluate``, ``amiro asr evaluate`` and ``amiro chat``."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from amiro.cli_support import add_json_flag, emit_json
from amiro.core.config import ConfigError
from amiro.dialogue.phrases import check_language


def register(sub: Any) -> None:
    nlu = sub.add_parser("nlu", help="natural-language understanding (en, ro, fr)")
    nlu_sub = nlu.add_subparsers(dest="nlu_command", metavar="COMMAND")
    parse = nlu_sub.add_parser("parse", help="one utterance through the NLU")
    parse.add_argument("--lang", default="en", help="en, ro or fr (default en)")
    parse.add_argument("text", nargs="+", help="the utterance")
    add_json_flag(parse)
    parse.set_defaults(handler=_parse)
    ev = nlu_sub.add_parser("evaluate", help="accuracy over labelled utterances (JSON lines)")
    ev.add_argument("file", type=Path, help='JSONL: {"lang", "text", "intent", "entities"}')
    add_json_flag(ev)
    ev.set_defaults(handler=_evaluate_nlu)
    nlu.set_defaults(handler=lambda args: _usage(nlu))

    asr = sub.add_parser("asr", help="speech recognition")
    asr_sub = asr.add_subparsers(dest="asr_command", metavar="COMMAND")
    aev = asr_sub.add_parser("evaluate", help="WER, sentence accuracy and RTF over WAV files")
    aev.add_argument("dir", type=Path, help="WAV files named by their transcript (or .txt)")
    aev.add_argument("--lang", default="en", help="language of the recordings (default en)")
    aev.add_argument("--backend", default="pocketsphinx", help="pocketsphinx, vosk or google")
    aev.add_argument("--grammar", default="nlu", help="pocketsphinx: nlu, answers or none (LM)")
    aev.add_argument("--vosk-model", type=Path, help="Vosk model directory")
    add_json_flag(aev)
    aev.set_defaults(handler=_evaluate_asr)
    asr.set_defaults(handler=lambda args: _usage(asr))

    chat = sub.add_parser("chat", help="talk to the dialogue module in a terminal")
    chat.add_argument("--lang", default="en", help="en, ro or fr (default en)")
    chat.add_argument("--voice", action="store_true", help="speak through the microphone")
    chat.set_defaults(handler=_chat)


def _usage(parser: argparse.ArgumentParser) -> int:
    parser.print_help()
    return 2


def _parse(args: argparse.Namespace) -> int:
    from amiro.dialogue.understanding import Nlu

    parsed = Nlu().parse(" ".join(args.text), check_language(args.lang))
    report = {
        "text": parsed.text,
        "lang": parsed.lang,
        "intent": {"name": parsed.intent, "confidence": round(parsed.confidence, 4)},
        "entities": parsed.entities,
        "ranking": [{"name": n, "confidence": round(c, 4)} for n, c in parsed.ranking],
    }
    if args.json:
        emit_json(report)
    else:
        ents = ", ".join(f"{k}={v}" for k, v in parsed.entities.items()) or "no entities"
        print(f"{parsed.intent} ({parsed.confidence:.2f}): {ents}")
    return 0


def _evaluate_nlu(args: argparse.Namespace) -> int:
    from amiro.dialogue.nlu_eval import evaluate, read_jsonl
    from amiro.dialogue.understanding import Nlu

    nlu = Nlu()
    report = evaluate(read_jsonl(args.file), lambda lang, text: nlu.parse(text, lang))
    if args.json:
        emit_json(report)
        return 0
    for lang, r in report.items():
        print(
            f"{lang}: n={r['n']} intent {100 * r['intent_accuracy']:.1f}% "
            f"entities {100 * r['entity_accuracy']:.1f}% {r['ms_per_utterance']:.2f} ms/utt"
        )
    return 0


def _evaluate_asr(args: argparse.Namespace) -> int:
    from amiro.dialogue.asr_eval import evaluate_asr
    from amiro.dialogue.config import AsrConfig, DialogueConfig
    from amiro.dialogue.stack import make_recognizer

    if args.backend not in ("pocketsphinx", "vosk", "google"):
        raise ConfigError(f"unknown asr backend '{args.backend}' (pocketsphinx, vosk, google)")
    asr = AsrConfig(backend=args.backend, grammar="nlu", vosk_model=args.vosk_model)
    recognizer = make_recognizer(DialogueConfig(asr=asr), args.grammar, check_language(args.lang))
    report = evaluate_asr(args.dir, recognizer)
    if args.json:
        emit_json(report)
    else:
        print(
            f"{report['files']} files: WER {100 * report['wer']:.1f}%, sentence accuracy "
            f"{100 * report['sentence_accuracy']:.1f}%, RTF {report['rtf']:.3f}"
        )
    return 0


def _chat(args: argparse.Namespace) -> int:
    from amiro.dialogue.chat import run_chat

    return run_chat(check_language(args.lang), args.voice)
