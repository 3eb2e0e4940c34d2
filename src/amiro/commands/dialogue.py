"""``amiro nlu parse|evaluate``, ``amiro asr evaluate`` and ``amiro chat``."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING, Any

from amiro.commands.support import add_command, add_group, emit_report, out_dir

if TYPE_CHECKING:
    from amiro.commands.support import Subcommands


def register(sub: Subcommands) -> None:
    nlu = add_group(sub, "nlu", "natural-language understanding (en, ro, fr)", dest="nlu_command")
    parse = add_command(nlu, "parse", _parse, help="one utterance through the NLU")
    parse.add_argument("--lang", default="en", help="en, ro or fr (default en)")
    parse.add_argument("text", nargs="+", help="the utterance")
    ev = add_command(
        nlu, "evaluate", _evaluate_nlu, help="accuracy over labelled utterances (JSON lines)"
    )
    ev.add_argument(
        "file",
        type=Path,
        nargs="*",
        help='JSONL: {"lang", "text", "intent", "entities"} or MASSIVE records (mapped onto '
        "amiro's labels); default: amiro's held-out files in en, ro and fr",
    )
    ev.add_argument("--out", type=Path, help="folder for the confusion plot (nlu_confusion.png)")

    nb = add_command(
        nlu, "bench", _bench_nlu, help="training time and ms per dialogue turn (NLU + manager)"
    )
    nb.add_argument("--repeats", type=int, default=3, help="passes over the held-out files")

    add_command(
        nlu,
        "choose-margin",
        _choose_margin,
        help="sweep the out-of-scope margin on MASSIVE dev (validation data)",
    )

    asr = add_group(sub, "asr", "speech recognition", dest="asr_command")
    aev = add_command(
        asr, "evaluate", _evaluate_asr, help="WER, sentence accuracy and RTF over WAV files"
    )
    aev.add_argument("dir", type=Path, help="WAV files named by their transcript (or .txt)")
    aev.add_argument("--lang", default="en", help="language of the recordings (default en)")
    aev.add_argument(
        "--backend",
        default="whisper",
        help="whisper (default; en, fr, ro), pocketsphinx (en), vosk, google, or a plugin's",
    )
    aev.add_argument(
        "--grammar",
        default="nlu",
        help="expected speech: nlu (commands), answers (yes/no/later) or none (free)",
    )
    aev.add_argument("--vosk-model", type=Path, help="Vosk model directory")
    aev.add_argument(
        "--reject-below",
        type=float,
        help="reject results with a lower confidence (default: the config's, 0.5; answers 0)",
    )
    aev.add_argument(
        "--out-of-grammar",
        type=Path,
        metavar="DIR",
        help="WAV files that must be rejected: adds false acceptance/rejection and a ROC table",
    )
    abn = add_command(
        asr, "bench", _bench_asr, help="Whisper's first load and real-time factor (5 s commands)"
    )
    abn.add_argument("--repeats", type=int, default=5, help="commands per language")
    syn = add_command(
        asr, "synthesize", _synthesize, help="speak commands into WAV files (espeak-ng, noise)"
    )
    syn.add_argument("file", type=Path, help="commands, one per line (# comments)")
    syn.add_argument("out", type=Path, help="directory for the WAV files")
    syn.add_argument("--snr", type=float, help="add white noise at this SNR in dB")
    syn.add_argument("--seed", type=int, default=0, help="noise seed (default 0)")
    syn.add_argument(
        "--noise-clips", type=int, default=0, metavar="N", help="also write N noise-only clips"
    )

    chat = add_command(
        sub, "chat", _chat, help="talk to the dialogue module in a terminal", with_json=False
    )
    chat.add_argument("--lang", default="en", help="en, ro or fr (default en)")
    chat.add_argument("--voice", action="store_true", help="speak through the microphone")
    chat.add_argument("--debug", action="store_true", help="also show the intent and entities")
    chat.add_argument(
        "--dm",
        type=Path,
        metavar="DIR",
        help="your own domain.yml, rules.yml, stories.yml, stories.<lang>.yml (amiro's for "
        "the files DIR lacks)",
    )


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
    import sys

    from amiro.dialogue.massive import read_labelled
    from amiro.dialogue.nlu_eval import evaluate, shipped_eval_files
    from amiro.dialogue.understanding import Nlu
    from amiro.evaluation.dialogue_confusion import plot, table

    files = args.file or shipped_eval_files()
    rows = [row for path in files for row in read_labelled(path)]
    nlu = Nlu()

    def progress(lang: str, done: int, total: int) -> None:
        if total >= 500:
            print(f"{lang}: {done}/{total}", file=sys.stderr, flush=True)

    report = evaluate(rows, lambda lang, text: nlu.parse(text, lang), progress)
    text = "\n\n".join(
        f"{lang}: {_describe(r)}\n{table(r['confusion'])}" for lang, r in report.items()
    )
    if args.out is not None:
        path = out_dir(args) / "nlu_confusion.png"
        names = ", ".join(p.name for p in files)
        plot(report, path, f"NLU confusion (rows: true intent, share of its utterances): {names}")
        text += f"\n\nconfusion plot: {path}"
    return emit_report(args, report, text)


def _bench_nlu(args: argparse.Namespace) -> int:
    from amiro.core.config import ConfigError
    from amiro.evaluation.dialogue_bench import bench

    if args.repeats < 1:
        raise ConfigError(f"--repeats {args.repeats}: must be 1 or more")
    report = bench(args.repeats)
    train = report["training_s"]
    text = f"training (MASSIVE {'on' if report['massive'] else 'not found'}): " + ", ".join(
        f"{lang} {s:.1f} s" for lang, s in train.items()
    )
    for lang, t in report["turn_ms"].items():
        text += f"\n{lang}: {t['median']:.2f} ms per turn (median), {t['p95']:.2f} ms (95th pct)"
    return emit_report(args, report, text)


def _choose_margin(args: argparse.Namespace) -> int:
    import sys

    from amiro.evaluation.dialogue_margin import sweep

    def progress(lang: str, done: int, total: int) -> None:
        if done == total:
            print(f"{lang}: {total} dev utterances", file=sys.stderr, flush=True)

    report = sweep(progress=progress)
    lines = [
        f"margin {m['margin']:.1f}: score {m['score']:.4f}  "
        + "  ".join(
            f"{lang} {100 * m[lang]['in_scope_accuracy']:.1f}/"
            f"{100 * m[lang]['out_of_scope_rejection']:.1f}"
            for lang in ("en", "ro", "fr")
        )
        for m in report["margins"]
    ]
    return emit_report(args, report, "\n".join([*lines, f"best: {report['best']}"]))


def _describe(r: dict[str, Any]) -> str:
    def pct(key: str) -> str:
        return "-" if r[key] is None else f"{100 * r[key]:.1f}%"

    return (
        f"n={r['n']} intent {pct('intent_accuracy')} entities {pct('entity_accuracy')} "
        f"in scope {pct('in_scope_accuracy')} out-of-scope refused "
        f"{pct('out_of_scope_rejection')} {r['ms_per_utterance']:.2f} ms/utt"
    )


def _evaluate_asr(args: argparse.Namespace) -> int:
    from amiro.core import registry
    from amiro.core.config import ConfigError
    from amiro.dialogue.asr_eval import (
        accuracy_report,
        describe_rates,
        rejection_report,
        transcribe_dir,
    )
    from amiro.dialogue.config import AsrConfig, DialogueConfig
    from amiro.dialogue.phrases import check_language
    from amiro.dialogue.stack import make_recognizer
    from amiro.dialogue.understanding import Nlu
    from amiro.evaluation.asr_intent import intent_report

    registry.resolve("asr", args.backend)  # an unknown name: one line with the choices
    defaults = AsrConfig(backend=args.backend)
    reject_below = args.reject_below
    if reject_below is None:
        answers = args.grammar == "answers"
        reject_below = defaults.listen_threshold if answers else defaults.reject_below
    if not 0.0 <= reject_below <= 1.0:
        raise ConfigError(f"--reject-below {reject_below}: must be between 0 and 1")
    # every result kept here: the report applies the thresholds itself
    asr = AsrConfig(backend=args.backend, vosk_model=args.vosk_model, reject_below=0.0)
    lang = check_language(args.lang)
    recognizer = make_recognizer(DialogueConfig(asr=asr), args.grammar, lang)
    heard = transcribe_dir(args.dir, recognizer, lang)
    report = accuracy_report(heard, reject_below, lang)
    text = (
        f"{report['files']} files: WER {100 * report['wer']:.1f}%, sentence accuracy "
        f"{100 * report['sentence_accuracy']:.1f}%, RTF {report['rtf']:.3f}, "
        f"{100 * report['rejected']:.1f}% rejected below {reject_below:g}"
    )
    nlu = Nlu()

    def intent_of(text: str) -> str:
        return nlu.parse(text, lang).intent

    intents = intent_report(args.dir, heard, reject_below, intent_of)
    report.update(intents)
    if intents["intent_accuracy"] is not None:
        text += f"\nintent from speech: {100 * intents['intent_accuracy']:.1f}% right"
        text += f" ({intents['in_scope_files']} commands)"
    if intents["out_of_context_acted_on"] is not None:
        text += f"\nout of context acted on: {100 * intents['out_of_context_acted_on']:.1f}%"
        text += f" ({intents['out_of_context_files']} recordings)"
    if args.out_of_grammar is not None:
        oog = transcribe_dir(args.out_of_grammar, recognizer, lang)
        rejection = rejection_report(heard, oog, reject_below, intent_of)
        report.update(rejection)
        text += "".join(f"\n{describe_rates(r)}" for r in rejection["roc"])
    return emit_report(args, report, text)


def _bench_asr(args: argparse.Namespace) -> int:
    from amiro.core.config import ConfigError
    from amiro.evaluation.asr_bench import bench

    if args.repeats < 1:
        raise ConfigError(f"--repeats {args.repeats}: must be 1 or more")
    report = bench(args.repeats)
    text = f"first load {report['first_load_s']:.2f} s; RTF on {report['command_s']:g} s commands: "
    text += ", ".join(
        f"{lang} {r['median']:.3f} (max {r['max']:.3f})" for lang, r in report["rtf"].items()
    )
    return emit_report(args, report, text)


def _synthesize(args: argparse.Namespace) -> int:
    import numpy as np

    from amiro.core.config import ConfigError
    from amiro.dialogue.asr_testset import read_commands, write_noise_clips, write_test_set
    from amiro.dialogue.tts import EspeakSynthesizer

    if args.noise_clips < 0:
        raise ConfigError(f"--noise-clips {args.noise_clips}: must be 0 or more")
    commands = read_commands(args.file)
    rng = np.random.default_rng(args.seed)
    written = write_test_set(commands, args.out, EspeakSynthesizer(), rng, args.snr)
    written += write_noise_clips(args.noise_clips, args.out, rng)
    report = {"files": len(written), "dir": str(args.out), "snr_db": args.snr}
    noise = "clean" if args.snr is None else f"white noise at {args.snr:g} dB SNR"
    return emit_report(args, report, f"{len(written)} WAV files in {args.out} ({noise})")


def _chat(args: argparse.Namespace) -> int:
    from amiro.dialogue.chat import run_chat
    from amiro.dialogue.phrases import check_language

    return run_chat(check_language(args.lang), args.voice, args.debug, args.dm)
