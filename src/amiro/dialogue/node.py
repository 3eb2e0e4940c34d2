"""The dialogue on the bus: commands heard (``/amiro/speech/heard``) go through the dialogue
manager, answers go out on ``/amiro/say``; and an optional TTS node that voices ``/amiro/say``
to WAV files or the speaker."""

from __future__ import annotations

from pathlib import Path

from amiro.core import names
from amiro.core.messages import SpeechHeard, SpeechRequest
from amiro.core.node import Node
from amiro.dialogue.audio import write_wav
from amiro.dialogue.manager import DialogueManager
from amiro.dialogue.profiles import SpeakerProfile, language_of
from amiro.dialogue.tts import Synthesizer

# Answers to the robot's own questions belong to the Listen task that asked them.
LISTEN_INTENTS = ("affirm", "deny", "postpone", "out_of_scope")


class DialogueNode(Node):
    def __init__(self, manager: DialogueManager, profiles: dict[str, SpeakerProfile]) -> None:
        super().__init__("dialogue")
        self.manager = manager
        self.profiles = profiles

    def on_start(self) -> None:
        self.say_pub = self.create_publisher(names.SAY, SpeechRequest)
        self.create_subscription(names.HEARD, SpeechHeard, self._on_heard, 10)

    def _on_heard(self, heard: SpeechHeard) -> None:
        user = heard.speaker or ""
        lang = heard.lang or language_of(self.profiles, user, "en")
        if not self.manager.awaiting(user):
            intent = self.manager.nlu.parse(heard.text, lang).intent
            if intent in LISTEN_INTENTS:
                return
        answer = self.manager.handle(heard.text, lang, user)
        self.say_pub.publish(
            SpeechRequest(
                answer.text, lang, display=answer.display, say=answer.say, act="dialogue_answer"
            )
        )


class TtsNode(Node):
    """Voices what the robot says with the speaker's voice: to numbered WAV files or the
    sound card (``sounddevice``)."""

    def __init__(
        self,
        synthesizer: Synthesizer,
        profiles: dict[str, SpeakerProfile],
        output: str,
        wav_dir: Path,
    ) -> None:
        super().__init__("tts")
        self.synthesizer = synthesizer
        self.profiles = profiles
        self.output = output
        self.wav_dir = wav_dir
        self.count = 0

    def on_start(self) -> None:
        self.create_subscription(names.SAY, SpeechRequest, self._on_say, 10)

    def _on_say(self, msg: SpeechRequest) -> None:
        if not msg.say:
            return
        profile = self.profiles.get(msg.addressee) or SpeakerProfile.model_validate(
            {"lang": msg.lang}
        )
        audio = self.synthesizer.synthesize(
            msg.text, msg.lang, profile.voice, profile.words_per_minute
        )
        self.count += 1
        if self.output == "wav":
            write_wav(self.wav_dir / f"say_{self.count:04d}.wav", audio)
        elif self.output == "speaker":
            import sounddevice  # type: ignore[import-untyped,import-not-found,unused-ignore]

            sounddevice.play(audio.samples, audio.rate)
