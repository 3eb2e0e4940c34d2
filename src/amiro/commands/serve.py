"""``amiro serve``: the whole system with the dashboard and, when configured, the MQTT bridge.

The handler imports the system and the web stack when called, so ``amiro --help`` stays fast.
"""

from __future__ import annotations

import argparse
import signal
import sys
import threading
from typing import TYPE_CHECKING

from amiro.commands.support import add_command

if TYPE_CHECKING:
    from types import FrameType

    from amiro.commands.support import Subcommands
    from amiro.core.clock import Clock
    from amiro.web.served import ServeConfig


def apply_flags(cfg: ServeConfig, args: argparse.Namespace) -> ServeConfig:
    """``--mqtt``, ``--home`` and ``--db`` override the system's environment section."""
    from amiro.core.config import parse
    from amiro.environment.config import EnvironmentConfig
    from amiro.environment.mqtt_bridge import MqttConfig, parse_url
    from amiro.web.served import ServeConfig

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
    from amiro.web.served import assemble, load_serve_config
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
