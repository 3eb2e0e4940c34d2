"""Pepper over NAOqi: amiro's robot port mapped onto ALTextToSpeech, ALTabletService,
ALMotion and ALRobotPosture.

``/amiro/say`` speaks in the request's language (``say(text, language)``) and shows the text
on the tablet; ``/amiro/display`` shows text or a web page; ``/amiro/head/cmd`` moves
HeadYaw/HeadPitch within their ranges; ``/cmd_vel`` becomes ``ALMotion.move`` in SI units
through the profile's limits; ``/amiro/posture`` goes to a named posture.  ``/odom`` comes
from ``ALMotion.getRobotPosition(True)`` and ``getRobotVelocity``.  Any channel can be left
to another adapter (Pepper's ROS 2 driver for the base, for instance).
"""

from __future__ import annotations

import html
import math
from collections.abc import Collection
from typing import Any
from urllib.parse import quote

from amiro.core import names
from amiro.core.messages import Header, JointState, Odometry, Pose2D, SpeechRequest, String, Twist
from amiro.core.node import Node
from amiro.core.safety import estop_engaged
from amiro.robot.frames import BASE_FRAME, ODOM_FRAME
from amiro.robot.limits import Planar, VelocityLimiter, clamp_head
from amiro.robot.naoqi_session import NaoqiSession
from amiro.robot.profile import Head, Naoqi, RobotProfile

NAOQI_CHANNELS = ("say", "display", "head", "base", "posture", "odom")

TTS, TABLET, MOTION, POSTURE = "ALTextToSpeech", "ALTabletService", "ALMotion", "ALRobotPosture"


def tablet_page(text: str) -> str:
    """A web page showing ``text`` large, for the tablet's web view (no server needed)."""
    body = html.escape(text).replace("\n", "<br>")
    page = (
        "<html><body style='font-family:sans-serif;font-size:6vw;display:flex;"
        f"align-items:center;justify-content:center;height:90vh'>{body}</body></html>"
    )
    return "data:text/html;charset=utf-8," + quote(page)


class NaoqiRobotNode(Node):
    """The robot port over one NAOqi session, for a profile with a ``naoqi`` section."""

    def __init__(
        self,
        naoqi: NaoqiSession,
        profile: RobotProfile,
        handles: Collection[str] = NAOQI_CHANNELS,
        odom_rate_hz: float = 10.0,
        name: str = "naoqi_robot",
    ) -> None:
        super().__init__(name)
        unknown = set(handles) - set(NAOQI_CHANNELS)
        if unknown:
            raise ValueError(f"unknown NAOqi channels {sorted(unknown)} (known: {NAOQI_CHANNELS})")
        if profile.naoqi is None or profile.head is None:
            raise ValueError(f"profile {profile.name} has no naoqi and head sections")
        self.naoqi = naoqi
        self.profile = profile
        self.settings: Naoqi = profile.naoqi
        self.head: Head = profile.head
        self.handles = frozenset(handles)
        self.odom_period = 1.0 / odom_rate_hz
        self.limiter = VelocityLimiter(profile.base, profile.limits)
        self.languages: set[str] | None = None  # what the robot's TTS has, once asked
        self.estop = False
        self._wanted, self._wanted_at = Twist(), -math.inf
        self._sent = Planar()
        self._odom_query: tuple[Any, Any] | None = None

    def on_start(self) -> None:
        self.limiter.reset()
        self._sent = Planar()
        self._languages_query = self.naoqi.query(TTS, "getAvailableLanguages")
        if "base" in self.handles and self.settings.wake_up:
            self.naoqi.call(MOTION, "wakeUp")
        if "posture" in self.handles and self.settings.posture_on_start:
            self._go_to(self.settings.posture_on_start)
        if "say" in self.handles:
            self.create_subscription(names.SAY, SpeechRequest, self._on_say, depth=50)
        if "display" in self.handles:
            self.create_subscription(names.DISPLAY, String, self._on_display)
        if "head" in self.handles:
            self.create_subscription(names.HEAD_CMD, JointState, self._on_head)
        if "posture" in self.handles:
            self.create_subscription(names.POSTURE, String, lambda m: self._go_to(m.data))
        if "base" in self.handles:
            self.create_subscription(names.CMD_VEL, Twist, self._on_cmd_vel, depth=1)
            self.create_subscription(names.EMERGENCY_STOP, String, self._on_estop)
            self.create_timer(1.0 / self.profile.cmd_rate_hz, self._send_command)
        if "odom" in self.handles:
            self.pub_odom = self.create_publisher(names.ODOM, Odometry)
            self.create_timer(self.odom_period, self._poll_odometry)
        self.create_timer(0.1, self._housekeeping)

    def on_stop(self) -> None:
        if "base" in self.handles:
            self.naoqi.call(MOTION, "stopMove")

    # --- speech and tablet --------------------------------------------------------------
    def language(self, code: str) -> str:
        """The robot's TTS language for an amiro code, or its default if not installed."""
        name = self.settings.languages.get(code, self.settings.default_language)
        if self.languages is not None and name not in self.languages:
            self.log.warning(
                "TTS has no %s on this robot; speaking %s", name, self.settings.default_language
            )
            return self.settings.default_language
        return name

    def _on_say(self, msg: SpeechRequest) -> None:
        if not msg.text.strip():
            return
        if msg.say:
            self.naoqi.call(TTS, "say", msg.text, self.language(msg.lang))
        if msg.display and "display" in self.handles:
            self.naoqi.call(TABLET, "showWebview", tablet_page(msg.text))

    def _on_display(self, msg: String) -> None:
        content = msg.data.strip()
        if not content:
            self.naoqi.call(TABLET, "hideWebview")
        elif content.startswith(("http://", "https://")):
            self.naoqi.call(TABLET, "showWebview", content)
        else:
            self.naoqi.call(TABLET, "showWebview", tablet_page(content))

    # --- head, posture, base ------------------------------------------------------------
    def _on_head(self, msg: JointState) -> None:
        targets = clamp_head(self.head, dict(zip(msg.name, msg.position, strict=False)))
        if targets:
            joint_names = {
                names.HEAD_YAW: self.head.yaw_joint,
                names.HEAD_PITCH: self.head.pitch_joint,
            }
            joints = [joint_names[j] for j in targets]
            self.naoqi.call(MOTION, "setAngles", joints, list(targets.values()), self.head.speed)

    def _go_to(self, posture: str) -> None:
        if posture.strip():
            self.naoqi.call(POSTURE, "goToPosture", posture.strip(), self.settings.posture_speed)

    def _on_cmd_vel(self, msg: Twist) -> None:
        self._wanted, self._wanted_at = msg, self.now()

    def _on_estop(self, msg: String) -> None:
        self.estop = estop_engaged(msg.data)
        if self.estop:
            self.limiter.reset()
            self._sent = Planar()
            self.naoqi.call(MOTION, "stopMove")

    def _send_command(self) -> None:
        """``ALMotion.move`` when the clamped command changes (each call costs a round trip)."""
        if self.estop:
            return
        fresh = self.now() - self._wanted_at <= self.profile.cmd_timeout_s
        target = self.limiter.target(self._wanted if fresh else Twist())
        command = self.limiter.step(target, 1.0 / self.profile.cmd_rate_hz)
        if command != self._sent:
            self.naoqi.call(MOTION, "move", command.vx, command.vy, command.wz)
            self._sent = command

    # --- odometry and bookkeeping -------------------------------------------------------
    def _poll_odometry(self) -> None:
        if self._odom_query is not None:
            position, velocity = self._odom_query
            if not (position.isFinished() and velocity.isFinished()):
                return
            self._odom_query = None
            if position.hasError() or velocity.hasError():
                self.naoqi.errors += 1
            else:
                self._publish_odometry(list(position.value()), list(velocity.value()))
        self._odom_query = (
            self.naoqi.query(MOTION, "getRobotPosition", True),
            self.naoqi.query(MOTION, "getRobotVelocity"),
        )

    def _publish_odometry(self, position: list[float], velocity: list[float]) -> None:
        x, y, theta = (float(v) for v in position[:3])
        vx, vy, wz = (float(v) for v in velocity[:3])
        self.pub_odom.publish(
            Odometry(
                Header(self.now(), ODOM_FRAME),
                BASE_FRAME,
                Pose2D(x, y, theta).to_pose(),
                Twist.planar(vx, vy, wz),
            )
        )

    def _housekeeping(self) -> None:
        if self.languages is None and self._languages_query.isFinished():
            if self._languages_query.hasError():
                self.languages = set(self.settings.languages.values())
            else:
                self.languages = {str(n) for n in self._languages_query.value()}
        self.naoqi.reap()
