"""``amiro serve``: the whole system with the dashboard and, when configured, the MQTT bridge.

The config file is a system config (``sim``, ``navigation``, ``environment``, ...) plus a
``web`` section.  Without a file, the simulated apartment with Maria on the couch.  The
functions import the system and the web stack when called, so ``amiro --help`` stays fast.
"""

from __future__ import annotations

import argparse
import os
import secrets
import signal
import sys
import threading
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from amiro.commands.support import add_command

if TYPE_CHECKING:
    from types import FrameType

    from fastapi import FastAPI
    from pydantic import SecretStr

    from amiro.commands.support import Subcommands
    from amiro.core.clock import Clock
    from amiro.core.runtime import Runtime
    from amiro.system import System, SystemConfig
    from amiro.web.auth import Authenticator
    from amiro.web.chat import ChatPort
    from amiro.web.config import WebConfig
    from amiro.web.gateway import GatewayNode


@dataclass(frozen=True)
class ServeConfig:
    system: SystemConfig
    web: WebConfig


def load_serve_config(path: str | None, seed: int = 1) -> ServeConfig:
    """The file's sections, or the default household (Maria, no scripted heat wave)."""
    from amiro.core.config import ConfigError, parse, read_yaml
    from amiro.scenarios.hydration import HydrationOptions, scenario_config
    from amiro.system import SystemConfig
    from amiro.web.config import WebConfig

    if path is None:
        system = scenario_config(HydrationOptions(seed=seed))
        data: dict[str, Any] = system.model_dump(mode="json")
        data["environment"]["sensors"]["changes"] = []
    else:
        raw = read_yaml(path)
        if raw is not None and not isinstance(raw, dict):
            raise ConfigError(f"{path}: expected a mapping at the top level")
        data = dict(raw or {})
    source = path or "<defaults>"
    web = parse(WebConfig, data.pop("web", None), f"{source}: web")
    return ServeConfig(parse(SystemConfig, data, source), web)


def apply_flags(cfg: ServeConfig, args: argparse.Namespace) -> ServeConfig:
    """``--mqtt``, ``--home`` and ``--db`` override the system's environment section."""
    from amiro.core.config import parse
    from amiro.environment.config import EnvironmentConfig
    from amiro.environment.mqtt_bridge import MqttConfig, parse_url

    env = cfg.system.environment
    if args.mqtt is not None:
        parse_url(args.mqtt)
        mqtt = (
            env.mqtt.model_copy(update={"url": args.mqtt})
            if env.mqtt
            else MqttConfig(url=args.mqtt)
        )
        env = env.model_copy(update={"mqtt": mqtt})
    if args.home is not None:
        env = parse(EnvironmentConfig, {**env.model_dump(), "home_id": args.home}, "--home")
    if args.db is not None:
        env = env.model_copy(update={"database": args.db})
    updates = {k: v for k, v in (("host", args.host), ("port", args.port)) if v is not None}
    system = cfg.system.model_copy(update={"environment": env})
    return ServeConfig(system, cfg.web.model_copy(update=updates))


def make_authenticator(web: WebConfig) -> Authenticator:
    from amiro.core.config import ConfigError
    from amiro.web.auth import Authenticator, hash_password

    password = web.admin_password or _secret_env("AMIRO_ADMIN_PASSWORD")
    if password is None or not password.get_secret_value():
        raise ConfigError("set the admin password in AMIRO_ADMIN_PASSWORD or web.admin_password")
    token = web.api_token or _secret_env("AMIRO_API_TOKEN")
    return Authenticator(
        web.admin_user,
        hash_password(password.get_secret_value()),
        os.environ.get("AMIRO_SECRET_KEY") or secrets.token_urlsafe(32),
        web.session_max_age_s,
        token.get_secret_value() if token else None,
    )


def _secret_env(name: str) -> SecretStr | None:
    from pydantic import SecretStr

    value = os.environ.get(name)
    return SecretStr(value) if value else None


@dataclass
class Served:
    system: System
    gateway: GatewayNode
    app: FastAPI

    @property
    def runtime(self) -> Runtime:
        return self.system.runtime

    def stop(self) -> None:
        self.system.stop()


def assemble(cfg: ServeConfig, clock: Clock, chat: ChatPort | None = None) -> Served:
    """The system, the gateway and the app (nothing started); the chat box talks to the
    system's dialogue manager unless another ``chat`` is given."""
    from amiro.system import build_system
    from amiro.web.api import Backend
    from amiro.web.app import create_app
    from amiro.web.chat import DialogueChat
    from amiro.web.gateway import GatewayNode
    from amiro.web.robot import SystemRobot

    system = build_system(cfg.system, clock)
    robot = SystemRobot(system)
    gateway = system.runtime.add(GatewayNode(robot, system.environment.devices))
    chat = chat or DialogueChat(system.dialogue.manager)
    backend = Backend(robot, system.environment, system.sensors, gateway, chat)
    app = create_app(backend, make_authenticator(cfg.web), cfg.web)
    return Served(system, gateway, app)


class RuntimeLoop:
    """Spins a runtime on its own thread until stopped (tests; the CLI uses the main thread)."""

    def __init__(self, runtime: Runtime, step_s: float = 0.05) -> None:
        self.runtime = runtime
        self.step_s = step_s
        self.stopping = threading.Event()
        self.thread = threading.Thread(target=self.run, name="amiro-runtime", daemon=True)

    def run(self) -> None:
        while not self.stopping.is_set():
            self.runtime.spin_for(self.step_s)

    def start(self) -> None:
        self.thread.start()

    def stop(self) -> None:
        self.stopping.set()
        self.thread.join(timeout=10)


def register(sub: Subcommands) -> None:
    p = add_command(
        sub,
        "serve",
        _serve,
        help="the whole system with the web dashboard (and MQTT when a broker is given)",
        description="Runs the simulated home (or a configured robot), all modules, the web "
        "dashboard and, with --mqtt or environment.mqtt, the MQTT bridge. The admin "
        "password comes from AMIRO_ADMIN_PASSWORD or web.admin_password.",
        with_json=False,
    )
    p.add_argument("--config", help="YAML system config with optional web: section")
    p.add_argument("--host", help="address to listen on (default 127.0.0.1)")
    p.add_argument("--port", type=int, help="port (default 8080)")
    p.add_argument("--mqtt", help="broker as mqtt://HOST:PORT")
    p.add_argument("--home", help="home id in the MQTT topics (default home)")
    p.add_argument("--db", help="health store URL (default: in memory)")
    p.add_argument("--speed", type=float, default=1.0, help="simulated s per real s (default 1)")
    p.add_argument("--seed", type=int, default=1, help="random seed (default 1)")


def _serve(args: argparse.Namespace) -> int:
    from amiro.core.clock import SimClock, WallClock
    from amiro.core.config import ConfigError
    from amiro.web.server import WebServer

    if args.speed <= 0:
        raise ConfigError(f"--speed must be positive, got {args.speed}")
    if args.port is not None and not 0 <= args.port <= 65535:
        raise ConfigError(f"--port must be in 0..65535, got {args.port}")
    cfg = apply_flags(load_serve_config(args.config, args.seed), args)
    real_robot = cfg.system.robot.adapter != "sim"
    if real_robot and args.speed != 1.0:
        raise ConfigError(f"--speed {args.speed:g}: a real robot runs in real time")
    clock: Clock = WallClock() if real_robot else SimClock(speed=args.speed)
    served = assemble(cfg, clock)
    server = WebServer(served.app, cfg.web.host, cfg.web.port)
    try:
        server.start()
    except RuntimeError as exc:
        served.stop()  # close the robot's connections
        raise ConfigError(f"{cfg.web.host}:{cfg.web.port}: {exc}") from None
    stopping = threading.Event()

    def _on_term(_sig: int, _frame: FrameType | None) -> None:
        stopping.set()

    signal.signal(signal.SIGTERM, _on_term)
    print(f"amiro serve: dashboard on {server.url}", file=sys.stderr)
    served.system.start()
    try:
        while not stopping.is_set():
            served.runtime.spin_for(0.05)
    except KeyboardInterrupt:
        pass
    finally:
        server.stop()
        served.stop()
    return 0
