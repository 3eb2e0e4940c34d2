"""Say, Listen and Display: the dialogue side of a behaviour."""

from __future__ import annotations

from typing import Any

from amiro.behavior.task import Task, TaskContext, TaskStatus
from amiro.core import names
from amiro.core.bus import Subscription
from amiro.core.messages import SpeechHeard, String
from amiro.dialogue.phrases import phrase


def _text(params: dict[str, Any], ctx: TaskContext, lang: str) -> str:
    if "text" in params:
        return str(params["text"])
    return phrase(str(params["phrase"]), lang, ctx.blackboard)


class Say(Task):
    """Say (and, by the paper's default, display) a phrase; succeeds once it is spoken.

    params: ``phrase`` (a template key) or ``text``; ``lang`` (default: blackboard ``lang``);
    ``act`` (the dialogue act, so listeners know what answer to expect); ``to`` (the
    person addressed, default blackboard ``person``).
    """

    type_name = "Say"

    def start(self, ctx: TaskContext) -> None:
        p = self.resolved(ctx)
        lang = str(p.get("lang", ctx.blackboard.get("lang", "en")))
        text = _text(p, ctx, lang)
        act = str(p.get("act", p.get("phrase", "")))
        addressee = str(p.get("to", ctx.blackboard.get("person", "")))
        duration = ctx.module("speech").say(text, lang, act, addressee)
        ctx.bus.publish(names.DISPLAY, String(text))
        self._until = ctx.now() + duration
        self.detail = {"text": text, "lang": lang}
        ctx.event("say", text=text, lang=lang)

    def update(self, ctx: TaskContext) -> TaskStatus:
        return TaskStatus.SUCCESS if ctx.now() >= self._until else TaskStatus.RUNNING


class Display(Task):
    """Show a phrase or text on the tablet."""

    type_name = "Display"

    def start(self, ctx: TaskContext) -> None:
        p = self.resolved(ctx)
        lang = str(p.get("lang", ctx.blackboard.get("lang", "en")))
        text = _text(p, ctx, lang)
        ctx.bus.publish(names.DISPLAY, String(text))
        self.detail = {"text": text}

    def update(self, ctx: TaskContext) -> TaskStatus:
        return TaskStatus.SUCCESS


class Listen(Task):
    """Wait for a spoken answer restricted to the expected intents (paper: Listen).

    params: ``expect`` (intents that mean success, default ``[affirm]``), ``timeout_s``
    (default 10).  Any other understood answer, or silence until the timeout, is a failure.
    The heard intent goes to the blackboard as ``last_intent``.
    """

    type_name = "Listen"

    def start(self, ctx: TaskContext) -> None:
        p = self.resolved(ctx)
        self.expect = [str(x) for x in p.get("expect", ["affirm"])]
        self.deadline = ctx.now() + float(p.get("timeout_s", 10.0))
        self.heard: list[SpeechHeard] = []
        self.sub: Subscription[SpeechHeard] | None = ctx.bus.subscribe(
            names.HEARD, SpeechHeard, self.heard.append, depth=5
        )

    def _close(self) -> None:
        if self.sub is not None:
            self.sub.destroy()
            self.sub = None

    def update(self, ctx: TaskContext) -> TaskStatus:
        for heard in self.heard:
            intent, confidence = ctx.module("nlu").intent(heard)
            ctx.blackboard["last_intent"] = intent
            self.detail = {"heard": heard.text, "intent": intent, "confidence": confidence}
            ctx.event("heard", text=heard.text, intent=intent, speaker=heard.speaker)
            self._close()
            return TaskStatus.SUCCESS if intent in self.expect else TaskStatus.FAILURE
        if ctx.now() >= self.deadline:
            self.detail = {"reason": "no_answer"}
            self._close()
            return TaskStatus.FAILURE
        return TaskStatus.RUNNING

    def cancel(self, ctx: TaskContext) -> None:
        self._close()
