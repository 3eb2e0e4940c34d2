"""Say, Listen and Display: the dialogue side of a behaviour."""

from __future__ import annotations

from pydantic import Field, model_validator

from amiro.behavior.task import Task, TaskContext, TaskParams, TaskStatus
from amiro.core import names
from amiro.core.bus import Subscription
from amiro.core.messages import SpeechHeard, String
from amiro.dialogue.grammar import ANSWER_INTENTS
from amiro.dialogue.phrases import phrase

REPROMPT = "answer_reprompt"


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
    (default 10), ``reprompts`` (default 1).  A yes, no or later (or an expected intent)
    ends the task: success when expected, else failure.  Anything else is no answer (speech
    the recogniser rejected, a question, talk to someone else): the robot asks again
    (phrase ``answer_reprompt``) up to ``reprompts`` times, then fails with the reason
    ``no_answer``, as after silence until the timeout.  The heard intent goes to the
    blackboard as ``last_intent``.
    """

    type_name = "Listen"

    class Params(TaskParams):
        expect: tuple[str, ...] = ("affirm",)
        timeout_s: float = Field(10.0, ge=0)
        reprompts: int = Field(1, ge=0)

    def start(self, ctx: TaskContext) -> None:
        p = self.bind(ctx, self.Params)
        self.expect = p.expect
        self.timeout_s = p.timeout_s
        self.reprompts = p.reprompts
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
        heard_now = list(self.heard)
        self.heard.clear()  # the subscription appends to this list
        for heard in heard_now:
            intent, confidence = ctx.need(ctx.modules.nlu, "nlu").intent(heard)
            ctx.blackboard["last_intent"] = intent
            self.detail = {"heard": heard.text, "intent": intent, "confidence": confidence}
            ctx.event("heard", text=heard.text, intent=intent, speaker=heard.speaker)
            if intent in self.expect or intent in ANSWER_INTENTS:
                self._close()
                return TaskStatus.SUCCESS if intent in self.expect else TaskStatus.FAILURE
            if self.reprompts > 0:
                self._reprompt(ctx, heard)
                return TaskStatus.RUNNING
            self.detail["reason"] = "no_answer"
            self._close()
            return TaskStatus.FAILURE
        if ctx.now() >= self.deadline:
            self.detail = {"reason": "no_answer"}
            self._close()
            return TaskStatus.FAILURE
        return TaskStatus.RUNNING

    def _reprompt(self, ctx: TaskContext, heard: SpeechHeard) -> None:
        """Not an answer: ask again, and listen as long again after the question."""
        self.reprompts -= 1
        lang = str(ctx.blackboard.get("lang", heard.lang))
        text = phrase(REPROMPT, lang, ctx.blackboard)
        addressee = heard.speaker or str(ctx.blackboard.get("person", ""))
        duration = ctx.need(ctx.modules.speech, "speech").say(text, lang, REPROMPT, addressee)
        ctx.bus.publish(names.DISPLAY, String(text))
        self.deadline = ctx.now() + duration + self.timeout_s
        ctx.event("reprompt", text=text, heard=heard.text, speaker=heard.speaker)

    def cancel(self, ctx: TaskContext) -> None:
        self._close()
