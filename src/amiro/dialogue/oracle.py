"""Oracle understanding for the simulator: trusts the intent label the simulated resident
attached to its reply.  A test and bootstrap backend, named as such; real NLU replaces it."""

from __future__ import annotations

from amiro.core.messages import SpeechHeard


class OracleUnderstanding:
    def intent(self, heard: SpeechHeard) -> tuple[str, float]:
        if heard.intent is None:
            return "out_of_scope", 0.0
        return heard.intent, heard.confidence
