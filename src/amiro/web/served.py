"""The whole system served with its dashboard: what ``amiro serve`` and a deployment's cloud
run.

The config file is a system config (``sim``, ``navigation``, ``environment``, ...) plus a
``web`` section.  Without a file, the simulated apartment with Maria on the couch.
"""

from __future__ import annotations

import os
import secrets
import threading
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from fastapi import FastAPI
    from pydantic import SecretStr

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
    from amiro.environment.days import clock_datetime
    from amiro.system import build_system
    from amiro.web.api import Backend
    from amiro.web.app import create_app
    from amiro.web.chat import DialogueChat
    from amiro.web.gateway import GatewayNode
    from amiro.web.health import seed_demo
    from amiro.web.robot import SystemRobot

    system = build_system(cfg.system, clock)
    robot = SystemRobot(system)
    gateway = system.runtime.add(GatewayNode(robot, system.environment.devices))
    chat = chat or DialogueChat(system.dialogue.manager)
    demo = False
    if cfg.web.demo_data and cfg.system.environment.database is None:
        residents = [p.name for p in cfg.system.people()]
        now = clock_datetime(clock)
        demo = seed_demo(system.environment.health, residents, now, cfg.system.seed)
    backend = Backend(robot, system.environment, system.sensors, gateway, chat, demo)
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
