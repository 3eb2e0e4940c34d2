"""``amiro launch``: start, watch and stop the processes of a deployment.

Each process is ``amiro node NAME --config FILE`` in its own OS process, sharing one
``ROS_DOMAIN_ID``.  The launcher restarts a process that dies (policy ``on-failure``), and
the deployment ends when a process marked ``ends_deployment`` exits, on timeout, or on a
signal; then every process gets SIGTERM (SIGKILL after ``stop_timeout_s``).  On several
machines, run ``amiro launch FILE --only NAME`` on each with ``localhost_only: false``.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO, Any, Literal

from pydantic import Field

from amiro.core.config import ConfigError, Section, load
from amiro.ros2.env import MAX_DOMAIN_ID, ros_environment


class ProcessSpec(Section):
    name: str
    config: Path
    restart: Literal["never", "on-failure"] = "on-failure"
    max_restarts: int = Field(default=3, ge=0)
    ends_deployment: bool = False


class DeploymentConfig(Section):
    name: str
    domain_id: int = Field(default=0, ge=0, le=MAX_DOMAIN_ID)
    localhost_only: bool = True
    seed: int = 1
    timeout_s: float = Field(default=600.0, gt=0)
    stop_timeout_s: float = Field(default=10.0, gt=0)
    processes: tuple[ProcessSpec, ...]


def load_deployment(path: Path) -> DeploymentConfig:
    dep = load(DeploymentConfig, path)
    base = path.resolve().parent
    specs = []
    for spec in dep.processes:
        config = spec.config if spec.config.is_absolute() else base / spec.config
        if not config.is_file():
            raise ConfigError(f"{path}: process {spec.name}: {config}: no such file")
        specs.append(spec.model_copy(update={"config": config}))
    names = [s.name for s in specs]
    if len(set(names)) != len(names):
        raise ConfigError(f"{path}: process names must be unique: {', '.join(names)}")
    return dep.model_copy(update={"processes": tuple(specs)})


@dataclass
class Child:
    spec: ProcessSpec
    popen: subprocess.Popen[bytes] | None = None
    restarts: int = 0
    exit_code: int | None = None
    log: IO[bytes] | None = None


@dataclass
class Launcher:
    """Runs a deployment's processes on this machine; ``events`` records what happened."""

    deployment: DeploymentConfig
    log_dir: Path
    only: tuple[str, ...] = ()
    domain_id: int | None = None
    children: dict[str, Child] = field(default_factory=dict)
    events: list[dict[str, Any]] = field(default_factory=list)

    def __post_init__(self) -> None:
        self.log_dir.mkdir(parents=True, exist_ok=True)
        unknown = set(self.only) - {s.name for s in self.deployment.processes}
        if unknown:
            raise ConfigError(f"no process named {', '.join(sorted(unknown))} in the deployment")
        self.children = {
            s.name: Child(s)
            for s in self.deployment.processes
            if not self.only or s.name in self.only
        }
        self._t0 = time.monotonic()

    def _event(self, kind: str, process: str, **detail: Any) -> None:
        record = {"t": round(time.monotonic() - self._t0, 3), "type": kind, "process": process}
        self.events.append({**record, **detail})
        print(f"launch: {kind} {process} {detail or ''}", file=sys.stderr, flush=True)

    def report_path(self, name: str) -> Path:
        return self.log_dir / f"{name}.json"

    def report(self, name: str) -> dict[str, Any]:
        """The JSON report process ``name`` wrote when it ended."""
        report: dict[str, Any] = json.loads(self.report_path(name).read_text(encoding="utf-8"))
        return report

    def log_path(self, name: str) -> Path:
        return self.log_dir / f"{name}.log"

    def events_path(self, name: str) -> Path:
        return self.log_dir / f"{name}.events.jsonl"

    def _command(self, spec: ProcessSpec) -> list[str]:
        domain = self.domain_id if self.domain_id is not None else self.deployment.domain_id
        return [
            sys.executable, "-m", "amiro.cli", "node", spec.name,
            "--config", str(spec.config),
            "--domain-id", str(domain),
            "--seed", str(self.deployment.seed),
            "--report", str(self.report_path(spec.name)),
            "--events", str(self.events_path(spec.name)),
        ]  # fmt: skip

    def _spawn(self, child: Child) -> None:
        domain = self.domain_id if self.domain_id is not None else self.deployment.domain_id
        env = {**os.environ, **ros_environment(domain, self.deployment.localhost_only)}
        child.log = self.log_path(child.spec.name).open("ab")
        child.popen = subprocess.Popen(
            self._command(child.spec), env=env, stdout=child.log, stderr=subprocess.STDOUT
        )
        child.exit_code = None
        self._event("started", child.spec.name, pid=child.popen.pid)

    def start(self) -> None:
        for child in self.children.values():
            self._spawn(child)

    def pid(self, name: str) -> int:
        popen = self.children[name].popen
        if popen is None:
            raise ConfigError(f"process {name} is not running")
        return popen.pid

    def poll(self) -> str | None:
        """Notice exits, restart per policy; returns the name of a process that ended the run."""
        for name, child in self.children.items():
            if child.popen is None or child.exit_code is not None:
                continue
            code = child.popen.poll()
            if code is None:
                continue
            child.exit_code = code
            self._event("exited", name, code=code)
            if child.spec.ends_deployment and code == 0:
                return name
            if child.spec.restart == "on-failure" and child.restarts < child.spec.max_restarts:
                child.restarts += 1
                self._event("restarting", name, restart=child.restarts)
                self._spawn(child)
            elif child.spec.ends_deployment:
                return name
        return None

    def run(self, period_s: float = 0.2) -> str:
        """Watch until the deployment ends; returns why ("<name> finished", "timeout")."""
        deadline = self._t0 + self.deployment.timeout_s
        while time.monotonic() < deadline:
            ended = self.poll()
            if ended is not None:
                code = self.children[ended].exit_code
                return f"{ended} finished" if code == 0 else f"{ended} failed"
            if all(c.exit_code is not None for c in self.children.values()):
                return "all exited"
            time.sleep(period_s)
        return "timeout"

    def run_all(self) -> str:
        """Start every process, watch until the deployment ends, then stop them all."""
        self.start()
        try:
            return self.run()
        finally:
            self.stop()

    def stop(self) -> None:
        """SIGTERM every live process, then SIGKILL those still running after the grace time."""
        live = [c for c in self.children.values() if c.popen is not None and c.popen.poll() is None]
        for child in live:
            assert child.popen is not None
            child.popen.send_signal(signal.SIGTERM)
        deadline = time.monotonic() + self.deployment.stop_timeout_s
        for child in live:
            assert child.popen is not None
            try:
                child.popen.wait(timeout=max(0.0, deadline - time.monotonic()))
            except subprocess.TimeoutExpired:
                child.popen.kill()
                child.popen.wait()
                self._event("killed", child.spec.name)
            child.exit_code = child.popen.returncode
            self._event("stopped", child.spec.name, code=child.exit_code)
        for child in self.children.values():
            if child.log is not None:
                child.log.close()

    def unclean_exits(self, tail_chars: int = 3000) -> dict[str, str]:
        """Processes that ended with a non-zero code, each with the end of its log."""
        return {
            name: self.log_path(name).read_text(errors="replace")[-tail_chars:]
            for name, child in self.children.items()
            if child.exit_code not in (0, None)
        }

    def summary(self) -> list[dict[str, Any]]:
        return [
            {"name": n, "restarts": c.restarts, "exit_code": c.exit_code}
            for n, c in self.children.items()
        ]
