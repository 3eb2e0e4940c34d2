"""What every shipped scenario does: configure, build, run to the end, and report."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from amiro.core.clock import SimClock, wall_seconds
from amiro.core.config import ConfigError, load
from amiro.scenarios.recorder import EventRecorder, stdout_or_none
from amiro.system import System, SystemConfig, build_system

LIVE_SPEED = 4.0  # simulated seconds per real second of the live log, unless --speed


def base_config_data(config_path: str | None, seed: int) -> dict[str, Any]:
    """The user's configuration (or the defaults) as data a scenario adds its parts to."""
    base = load(SystemConfig, config_path) if config_path else SystemConfig()
    data: dict[str, Any] = base.model_dump(exclude_unset=True)
    data["seed"] = seed
    return data


@dataclass
class ScenarioRun:
    """A finished run: the system (stopped), what was recorded and the timing."""

    system: System
    recorder: EventRecorder
    sim_time_s: float
    wall_time_s: float

    def timing(self) -> dict[str, Any]:
        wall = self.wall_time_s
        return {
            "sim_time_s": round(self.sim_time_s, 3),
            "wall_time_s": round(wall, 3),
            "speedup": round(self.sim_time_s / wall, 1) if wall > 0 else None,
        }


def run_scenario(
    cfg: SystemConfig,
    finished: Callable[[System], bool],
    *,
    live: bool,
    speed: float | None,
    timeout_s: float,
    setup: Callable[[System], None] | None = None,
) -> ScenarioRun:
    """Build the system, let ``setup`` add to it, spin until ``finished`` (or the timeout)."""
    if cfg.robot.adapter != "sim":
        raise ConfigError(
            f"robot.adapter: {cfg.robot.adapter}: scenarios script the simulated home's "
            "residents and need the simulator (robot.adapter: sim); on a real robot use "
            "`amiro serve --config` and trigger behaviours there"
        )
    speed = speed if speed is not None else (LIVE_SPEED if live else None)
    if speed is not None and speed <= 0:
        raise ConfigError(f"--speed must be positive, got {speed:g}")
    system = build_system(cfg, SimClock(speed=speed))
    recorder = EventRecorder(system.runtime, live=stdout_or_none(live))
    if setup is not None:
        setup(system)
    started = wall_seconds()
    system.start()
    system.runtime.spin_until(lambda: finished(system), timeout_s)
    system.runtime.spin_for(0.5)  # let the last messages reach every listener
    wall = wall_seconds() - started
    sim_time = system.runtime.clock.now()
    system.stop()
    return ScenarioRun(system, recorder, sim_time, wall)
