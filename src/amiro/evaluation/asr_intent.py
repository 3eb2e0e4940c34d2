"""Intent from speech: what the robot would do with what it heard.  Each recording's
reference intent is its sidecar ``.intent`` (one label), else the NLU's reading of the
reference transcript; a rejected transcript is "not understood" (``out_of_scope``).

- ``intent_accuracy``: recordings with an in-scope reference intent whose transcript the NLU
  reads as that intent;
- ``out_of_context_acted_on``: recordings whose reference is ``out_of_scope`` (speech the
  robot must not act on) whose accepted transcript the NLU reads as some command."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from amiro.dialogue.asr import gate
from amiro.dialogue.asr_eval import Heard
from amiro.dialogue.schema import OUT_OF_SCOPE


def reference_intent(wav: Path, reference: str, intent_of: Callable[[str], str]) -> str:
    sidecar = wav.with_suffix(".intent")
    if sidecar.is_file():
        return sidecar.read_text(encoding="utf-8").strip()
    return intent_of(reference)


def intent_report(
    directory: Path,
    heard: list[Heard],
    reject_below: float,
    intent_of: Callable[[str], str],
) -> dict[str, Any]:
    rows = []
    for h in heard:
        text = gate(h.transcript, reject_below).text
        rows.append(
            {
                "file": h.file,
                "reference_intent": reference_intent(directory / h.file, h.reference, intent_of),
                "intent": intent_of(text) if text else OUT_OF_SCOPE,
            }
        )
    in_scope = [r for r in rows if r["reference_intent"] != OUT_OF_SCOPE]
    out = [r for r in rows if r["reference_intent"] == OUT_OF_SCOPE]
    right = sum(r["intent"] == r["reference_intent"] for r in in_scope)
    acted = sum(r["intent"] != OUT_OF_SCOPE for r in out)
    return {
        "in_scope_files": len(in_scope),
        "intent_accuracy": right / len(in_scope) if in_scope else None,
        "out_of_context_files": len(out),
        "out_of_context_acted_on": acted / len(out) if out else None,
        "intents": rows,
    }
