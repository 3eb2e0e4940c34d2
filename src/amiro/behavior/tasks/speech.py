"""Say, Listen and Display: the dialogue side of a behaviour."""

from __future__ import annotations

from pydantic import Field, model_validator

from amiro.behavior.task import Task, TaskContext, TaskParams, TaskStatus
from amiro.core import names
from amiro.core.bus import Subscription
from amiro.core.messages import SpeechHeard, String
from amiro.dialogue.phrases import phrase


class TextParams(TaskParams):
    """What to say or show: a ``phrase`` template key or a literal ``text``."""

    phrase: str | None = None
    text: str | None = None
    lang: str | None = None

    @model_validator(mode="after")
    def _something_to_say(self) -> TextParams:
        if self.phrase is None and self.text is None:
            raise ValueError("needs a 'phrase' or a 'text' parameter")
        return self

    def words(self, ctx: TaskContext) -> tuple[str, str]:
        """The text (``text`` wins over ``phrase``) and its language (default: blackboard
        ``lang``)."""
        lang = self.lang if self.lang is not None else str(ctx.blackboard.get("lang", "en"))
        if self.text is not None:
            return self.text, lang
        assert self.phrase is not None  # the validator above
        return phrase(self.phrase, lang, ctx.blackboard), lang


class Say(Task):
    """Say (and, by the paper's default, display) a phrase; succeeds once it is spoken.

    params: ``phrase`` (a template key) or ``text``; ``lang`` (default: blackboard ``lang``);
    ``act`` (the dialogue act, so listeners know what answer to expect); ``to`` (the
    person addressed, default blackboard ``person``).
    """

    type_name = "Say"

    class Params(TextParams):
        act: str | None = None
        to: str | None = None

    def start(self, ctx: TaskContext) -> None:
        p = self.bind(ctx, self.Params)
        text, lang = p.words(ctx)
        act = p.act if p.act is not None else (p.phrase or "")
        addressee = p.to if p.to is not None else str(ctx.blackboard.get("person", ""))
        duration = ctx.need(ctx.modules.speech, "speech").say(text, lang, act, addressee)
        ctx.bus.publish(names.DISPLAY, String(text))
        self._until = ctx.now() + duration
        self.detail = {"text": text, "lang": lang}
        ctx.event("say", text=text, lang=lang)

    def update(self, ctx: TaskContext) -> TaskStatus:
        return TaskStatus.SUCCESS if ctx.now() >= self._until else TaskStatus.RUNNING


class Display(Task):
    """Show a phrase or text on the tablet."""

    type_name = "Display"

    class Params(TextParams):
        pass

    def start(self, ctx: TaskContext) -> None:
        text, _ = self.bind(ctx, self.Params).words(ctx)
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

    class Params(TaskParams):
        expect: tuple[str, ...] = ("affirm",)
        timeout_s: float = Field(10.0, ge=0)

    def start(self, ctx: TaskContext) -> None:
        p = self.bind(ctx, self.Params)
        self.expect = p.expect
        self.deadline = ctx.now() + p.timeout_s
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
            intent, confidence = ctx.need(ctx.modules.nlu, "nlu").intent(heard)
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
