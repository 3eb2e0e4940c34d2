"""One deployment process: its runtime, its role, the bridge, and a clean shutdown.

The ``sim`` role owns time (a paced SimClock, published on ``/clock``) and waits for the
processes named in ``wait_for`` before starting it; the other roles follow that clock, or
with ``clock: wall`` run on wall time beside a real robot's driver.
SIGTERM and SIGINT stop the process cleanly at its next step: nodes stopped, rclpy shut
down, report written.
"""

from __future__ import annotations

import json
import logging
import signal
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import asdict
from pathlib import Path
from types import FrameType
from typing import Any, TextIO

from amiro.core import names
from amiro.core.clock import Clock, SimClock, WallClock, wall_seconds
from amiro.core.config import ConfigError, load
from amiro.core.messages import Acknowledgement, BehaviorEvent
from amiro.core.runtime import Runtime
from amiro.deploy.config import NodeConfig
from amiro.deploy.interfaces import known_action, known_service
from amiro.deploy.nav2 import add_nav2_navigation, uses_nav2
from amiro.deploy.parameters import declare_parameters
from amiro.deploy.robot_edge import build_robot_edge
from amiro.deploy.roles import BUILDERS
from amiro.home.world import World
from amiro.ros2.actions import ActionExporter, RemoteActionServer
from amiro.ros2.bridge import Ros2Bridge
from amiro.ros2.clock import ClockPublisher, ClockStoppedError, FollowedClock
from amiro.ros2.context import RosContext
from amiro.ros2.endpoint import WireEndpoint
from amiro.ros2.hri import HriListener, HriPublisher
from amiro.ros2.services import RemoteService, ServiceExporter
from amiro.scenarios.hydration import HydrationOptions, scenario_config
from amiro.system import SystemConfig, home_path

log = logging.getLogger("amiro.deploy.process")


class EventLog:
    """Behaviour events and acknowledgements seen by this process, optionally as JSON lines."""

    def __init__(self, runtime: Runtime, out: TextIO | None = None) -> None:
        self.runtime = runtime
        self.events: list[dict[str, Any]] = []
        self.acks: list[Acknowledgement] = []
        self.out = out
        runtime.bus.subscribe(names.EVENTS, BehaviorEvent, self._on_event, depth=10_000)
        runtime.bus.subscribe(names.ACK, Acknowledgement, self._on_ack, depth=1000)

    def _write(self, record: dict[str, Any]) -> None:
        if self.out is not None:
            self.out.write(json.dumps(record, default=str) + "\n")
            self.out.flush()

    def _on_event(self, event: BehaviorEvent) -> None:
        record = event.to_dict()
        self.events.append(record)
        self._write(record)

    def _on_ack(self, ack: Acknowledgement) -> None:
        self.acks.append(ack)
        self._write(
            {
                "t": round(self.runtime.clock.now(), 3),
                "type": "ack_received",
                "id": ack.id,
                "status": ack.status,
            }
        )


def system_config(node: NodeConfig, seed: int) -> SystemConfig:
    if node.scenario == "hydration":
        path = str(node.system) if node.system is not None else None
        return scenario_config(HydrationOptions(seed=seed, config_path=path))
    return load(SystemConfig, node.system) if node.system is not None else SystemConfig()


class StopRequest:
    """Set by SIGTERM/SIGINT; the run loop and the followed clock poll it.

    The handler only sets flags: an exception raised at an arbitrary bytecode (the old
    KeyboardInterrupt) could land inside rclpy's executor and make its shutdown fail.
    """

    def __init__(self) -> None:
        self.requested = False
        self.clock: FollowedClock | None = None

    def __call__(self, signum: int, frame: FrameType | None) -> None:
        self.requested = True
        if self.clock is not None:
            self.clock.stopping = True


@contextmanager
def _stop_on_signals(stop: StopRequest) -> Iterator[None]:
    previous = {s: signal.signal(s, stop) for s in (signal.SIGTERM, signal.SIGINT)}
    try:
        yield
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)


def run_process(
    process: str,
    node: NodeConfig,
    seed: int = 1,
    events_path: Path | None = None,
) -> dict[str, Any]:
    """Run one process until its stop condition or a signal; returns its report."""
    stop = StopRequest()
    if events_path is not None:  # the launcher's log dir holds what a process leaves behind
        node = node.with_ledger_base(events_path.parent)
    with _stop_on_signals(stop):
        return _run_process(process, node, seed, events_path, stop)


def _run_process(
    process: str, node: NodeConfig, seed: int, events_path: Path | None, stop: StopRequest
) -> dict[str, Any]:
    cfg = system_config(node, seed)
    served = [known_action(name) for name in node.serve_actions]
    called = [known_action(name) for name in node.call_actions]
    exported = [known_service(name) for name in node.serve_services]
    imported = [known_service(name) for name in node.call_services]
    ros = RosContext(node.ros_node_name(process), node.ros.domain_id, node.ros.localhost_only)
    declare_parameters(ros, node, cfg)
    clock = _process_clock(node, ros)
    if isinstance(clock, FollowedClock):
        stop.clock = clock
        clock.stopping = stop.requested
    runtime = Runtime(clock, seed=seed)
    robot = node.role == "edge" and cfg.robot.adapter != "sim"  # a real robot's adapters
    bridge = runtime.add(
        Ros2Bridge(
            ros, node.topics_out(robot), node.topics_in(robot), node.remap, name="ros2_bridge"
        )
    )
    endpoints: list[WireEndpoint] = [runtime.add(ActionExporter(ros, codec)) for codec in served]
    endpoints += [
        runtime.add(RemoteActionServer(ros, codec, node.action_timeout_s)) for codec in called
    ]
    if node.role == "edge" and node.hri:  # the people perception tracks, on ROS4HRI too
        runtime.add(HriPublisher(ros))
    if node.role == "edge" and cfg.perception.backend == "hri":  # another HRI stack's people
        runtime.add(HriListener(ros, names.HRI_PEOPLE))
    if node.role == "edge" and uses_nav2(cfg):  # MoveTo and primitives: the robot's Nav2
        world = World.load(home_path(cfg), cfg.sim.resolution)
        endpoints += add_nav2_navigation(runtime, ros, cfg, world, node.action_timeout_s)
    services: list[WireEndpoint] = [runtime.add(ServiceExporter(ros, s)) for s in exported]
    services += [runtime.add(RemoteService(ros, spec)) for spec in imported]
    parts = (build_robot_edge if robot else BUILDERS[node.role])(runtime, process, node, cfg)
    out = events_path.open("a", encoding="utf-8") if events_path is not None else None
    events = EventLog(runtime, out)
    started = wall_seconds()
    outcome = "stopped"
    try:
        outcome = _run(runtime, ros, clock, node, events, stop)
    finally:
        if isinstance(clock, FollowedClock):
            clock.stopping = True
        runtime.stop()
        parts.close()
        ros.close()
        if out is not None:
            out.close()
    return {
        "process": process,
        "role": node.role,
        "outcome": outcome,
        "sim_time_s": round(runtime.clock.now(), 3),
        "wall_time_s": round(wall_seconds() - started, 3),
        "bridge": {
            "out": bridge.stats.out,
            "in": bridge.stats.inbound,
            "errors": bridge.stats.errors,
            "skipped": bridge.skipped,
        },
        "actions": {e.name: asdict(e.stats) for e in endpoints},
        "services": {e.name: asdict(e.stats) for e in services},
        "acks": [{"id": a.id, "status": a.status, "ts": a.ts} for a in events.acks],
        "events": events.events,
        **parts.summary(),
    }


def _process_clock(node: NodeConfig, ros: RosContext) -> Clock:
    if node.role == "sim":
        return SimClock(speed=node.speed)
    return WallClock() if node.clock == "wall" else FollowedClock(ros)


def _run(
    runtime: Runtime,
    ros: RosContext,
    clock: Clock,
    node: NodeConfig,
    events: EventLog,
    stop: StopRequest,
) -> str:
    if isinstance(clock, FollowedClock):
        if not clock.wait_first(node.wait_timeout_s):
            if stop.requested:
                return "stopped"
            raise ConfigError(
                f"no /clock within {node.wait_timeout_s:g} s: is the robot process up?"
            )
    elif node.role == "sim":
        runtime.add(ClockPublisher(ros))
        missing = ros.wait_for_nodes(
            list(node.wait_for), node.wait_timeout_s, cancelled=lambda: stop.requested
        )
        if missing:
            log.warning("starting without %s (not on the ROS graph)", ", ".join(missing))
    if stop.requested:
        return "stopped"
    runtime.start()
    origin = runtime.clock.now() if isinstance(clock, WallClock) else 0.0  # sim time: from 0
    try:
        while not stop.requested:
            if node.duration_s is not None and runtime.clock.now() - origin >= node.duration_s:
                return "duration"
            if node.stop_after_acks is not None and len(events.acks) >= node.stop_after_acks:
                runtime.spin_for(0.5)  # let the last events arrive
                return "acknowledged"
            runtime.spin_for(0.25)
    except ClockStoppedError:
        pass
    return "stopped"
