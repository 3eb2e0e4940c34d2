"""Speed of the core: bus messages, engine task dispatches, simulator steps with the lidar.

Measured as rates on this machine (never asserted in tests): ``amiro bench core``.
"""

from __future__ import annotations

from typing import Any

import amiro.behavior.tasks  # noqa: F401 - registers Wait
from amiro.behavior.engine import BehaviorEngine
from amiro.behavior.graph import TaskGraph
from amiro.behavior.task import make_task
from amiro.core import names
from amiro.core.clock import wall_seconds
from amiro.core.messages import String, Twist
from amiro.core.runtime import Runtime
from amiro.sim.config import SimConfig
from amiro.sim.simulator import build_sim


def bench_bus(messages: int = 200_000, batch: int = 1000) -> float:
    """Messages per second published and delivered to one subscriber."""
    rt = Runtime()
    received = [0]

    def count(_: String) -> None:
        received[0] += 1

    rt.bus.subscribe("/bench", String, count, depth=batch)
    pub = rt.bus.publisher("/bench", String)
    msg = String("x")
    start = wall_seconds()
    for _ in range(messages // batch):
        for _ in range(batch):
            pub.publish(msg)
        rt.bus.spin_some()
    elapsed = wall_seconds() - start
    assert received[0] == messages
    return messages / elapsed


def bench_engine(tasks: int = 5000) -> float:
    """Tasks dispatched (started, run to completion, successor chosen) per second."""
    rt = Runtime()
    engine = rt.add(BehaviorEngine())
    graph = TaskGraph("bench", priority=1)
    for i in range(tasks):
        successor = f"t{i + 1}" if i + 1 < tasks else None  # the last one ends the graph
        graph.add(f"t{i}", make_task("Wait", {"seconds": 0.0}), on_success=successor)
    rt.start()
    run = engine.submit(graph)
    start = wall_seconds()
    rt.spin_until(lambda: run.done, timeout=tasks * 1.0)
    elapsed = wall_seconds() - start
    assert len(run.records) == tasks
    return tasks / elapsed


def bench_sim(sim_seconds: float = 60.0) -> dict[str, float]:
    """Physics steps per second with the lidar on and the robot turning in place."""
    rt = Runtime(seed=1)
    sim = build_sim(rt, SimConfig())
    cmd = rt.bus.publisher(names.CMD_VEL, Twist)
    rt.create_timer(0.1, lambda: cmd.publish(Twist.planar(0.0, 0.0, 0.5)))
    rt.start()
    start = wall_seconds()
    rt.spin_for(sim_seconds)
    elapsed = wall_seconds() - start
    return {
        "sim_steps_per_s": sim.robot.steps / elapsed,
        "sim_realtime_factor": sim_seconds / elapsed,
    }


def bench_lidar(scans: int = 300) -> float:
    """Milliseconds per 360-beam scan of the default apartment, from poses across it."""
    rt = Runtime(seed=1)
    sim = build_sim(rt, SimConfig())
    grid, lidar = sim.world.live, sim.robot.lidar
    poses = [sim.world.place(name) for name in sim.world.home.places]
    start = wall_seconds()
    for i in range(scans):
        lidar.scan(grid, poses[i % len(poses)], 0.0, rt.rng)
    return (wall_seconds() - start) * 1000.0 / scans


def bench_core() -> dict[str, Any]:
    out: dict[str, Any] = {
        "bus_msgs_per_s": round(bench_bus()),
        "engine_dispatches_per_s": round(bench_engine()),
    }
    out.update({k: round(v, 1) for k, v in bench_sim().items()})
    out["lidar_ms_per_scan"] = round(bench_lidar(), 3)
    return out
