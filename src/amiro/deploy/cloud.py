"""What the cloud process adds for the people in the home: dialogue and the dashboard.

The paper's section 3.1 runs dialogue, environment, health and web in the cloud.  Here the
cloud builds the dialogue stack when it serves understanding to the edge, asks the edge for
behaviours, or serves the dashboard; with ``web:`` it also builds the smart environment
(health store, devices, reminders, ledger) and serves the same dashboard app as ``amiro
serve``, fed by bridged topics through :class:`~amiro.deploy.web_robot.RemoteRobot`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from amiro.behavior.loader import load_behavior
from amiro.core import names
from amiro.core.config import ConfigError
from amiro.core.messages import SpeechRequest
from amiro.core.node import Node
from amiro.core.runtime import Runtime
from amiro.deploy.behaviors import BehaviorRequests
from amiro.deploy.config import NodeConfig
from amiro.deploy.dialogue import DialogueBehaviors, UnderstandingService
from amiro.deploy.web_robot import RemoteRobot
from amiro.dialogue.profiles import household_voices
from amiro.dialogue.stack import Dialogue, build_dialogue, text_hearing
from amiro.environment.assembly import Environment, add_environment
from amiro.environment.rules import RulesNode
from amiro.environment.simulated import SimulatedSensorsNode
from amiro.home.world import HomeSpec
from amiro.system import SHIPPED_BEHAVIORS, SystemConfig, shipped_behavior
from amiro.system.dialogue_sources import environment_sources
from amiro.web.config import WebConfig
from amiro.web.server import WebServer


class WebServerNode(Node):
    """Stops the dashboard's server with the process, then closes the stores it served (the
    server is started when built, so that a busy port is a configuration error, not a node
    failure)."""

    def __init__(self, server: WebServer, environment: Environment) -> None:
        super().__init__("web_server")
        self.server = server
        self.environment = environment

    def on_stop(self) -> None:
        self.server.stop()
        self.environment.close()


@dataclass
class CloudServices:
    dialogue: Dialogue | None = None
    understanding: UnderstandingService | None = None
    requests: BehaviorRequests | None = None
    behaviors: DialogueBehaviors | None = None
    web_url: str | None = None  # the dashboard's address, bound port included

    def summary(self) -> dict[str, Any]:
        report: dict[str, Any] = {}
        if self.understanding is not None:
            report["understood"] = [
                {"intent": u.intent, "confidence": round(u.confidence, 3)}
                for u in self.understanding.answered
            ]
        if self.requests is not None:
            report["behavior_requests"] = [r.to_dict() for r in self.requests.requests]
        if self.behaviors is not None:
            report["dialogue_outcomes"] = list(self.behaviors.answers)
        if self.web_url is not None:
            report["web"] = self.web_url
        return report


def pose_topic(cfg: SystemConfig) -> str:
    """Where the robot's pose estimate is published (what MoveTo itself listens to)."""
    return names.GROUND_TRUTH if cfg.navigation.localization == "oracle" else names.LOCALIZATION


def behavior_kinds(cfg: SystemConfig) -> dict[str, int]:
    """The behaviours an edge built from ``cfg`` knows, each with its own priority."""
    files = {name: shipped_behavior(name) for name in SHIPPED_BEHAVIORS}
    files.update(cfg.behavior.handlers)
    return {kind: load_behavior(files[kind]).priority for kind in sorted(files)}


def add_cloud_services(
    runtime: Runtime,
    node: NodeConfig,
    cfg: SystemConfig,
    home: HomeSpec,
    sensors: SimulatedSensorsNode,
    rules: RulesNode,
) -> CloudServices:
    remote_behaviors = names.BEHAVIOR_RUN in node.call_actions
    if node.web is not None and not remote_behaviors:
        raise ConfigError(f"web: the dashboard needs call_actions: [{names.BEHAVIOR_RUN}]")
    serves_understanding = names.UNDERSTAND in node.serve_services
    if not (node.web is not None or remote_behaviors or serves_understanding):
        return CloudServices()
    rooms = list(home.rooms)
    services = CloudServices()
    environment = None
    if node.web is not None:
        environment = add_environment(runtime, rooms, cfg.environment, sensors, rules)
    if remote_behaviors:
        services.requests = runtime.add(BehaviorRequests())
        say = runtime.bus.publisher(names.SAY, SpeechRequest)
        services.behaviors = DialogueBehaviors(services.requests, say)
    voices = household_voices(cfg.people())
    sources = None if environment is None else environment_sources(runtime, environment, rooms)
    services.dialogue = build_dialogue(
        runtime, text_hearing(cfg.dialogue), voices, submit=services.behaviors, sources=sources
    )
    if serves_understanding:
        services.understanding = runtime.add(UnderstandingService(services.dialogue.nlu))
    if node.web is not None and environment is not None and services.requests is not None:
        robot = RemoteRobot(home, behavior_kinds(cfg), pose_topic(cfg), services.requests)
        services.web_url = _serve(
            runtime, node.web, runtime.add(robot), environment, sensors, services.dialogue
        )
    return services


def _serve(
    runtime: Runtime,
    web: WebConfig,
    robot: RemoteRobot,
    environment: Environment,
    sensors: SimulatedSensorsNode,
    dialogue: Dialogue,
) -> str:
    from amiro.web.api import Backend
    from amiro.web.app import create_app
    from amiro.web.chat import DialogueChat
    from amiro.web.gateway import GatewayNode
    from amiro.web.served import make_authenticator

    gateway = runtime.add(GatewayNode(robot, environment.devices))
    backend = Backend(robot, environment, sensors, gateway, DialogueChat(dialogue.manager))
    app = create_app(backend, make_authenticator(web), web)
    server = WebServer(app, web.host, web.port)
    try:
        server.start()
    except RuntimeError as exc:
        raise ConfigError(f"web: {web.host}:{web.port}: {exc}") from None
    runtime.add(WebServerNode(server, environment))
    return server.url
