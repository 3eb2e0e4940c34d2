"""Recording the embedded hydration run, and replaying a file (optionally onto ROS 2)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from amiro.core.clock import SimClock
from amiro.core.config import ConfigError
from amiro.core.runtime import Runtime
from amiro.recording.mcap_file import McapRecorder, McapReplayer, read_mcap
from amiro.scenarios.hydration import HydrationOptions, scenario_config
from amiro.system import build_system


def record_hydration(out: Path, seed: int = 1, topics: list[str] | None = None) -> dict[str, Any]:
    system = build_system(scenario_config(HydrationOptions(seed=seed)))
    recorder = McapRecorder(out, topics)
    system.start()
    system.runtime.add(recorder)  # last: it records the topics the other nodes created

    def finished() -> bool:
        runs = [r for r in system.engine.runs.values() if r.name == "hydration"]
        return bool(runs) and runs[0].done and not system.notifications.runs

    system.runtime.spin_until(finished, 900.0)
    system.runtime.spin_for(0.5)
    system.stop()
    runs = [r.outcome for r in system.engine.runs.values()]
    return {
        "file": str(out),
        "outcome": runs[0] if runs else "timeout",
        "sim_time_s": round(system.runtime.clock.now(), 3),
        "messages": sum(recorder.counts.values()),
        "topics": dict(sorted(recorder.counts.items())),
    }


def replay(
    path: Path, speed: float | None = None, ros2: bool = False, domain_id: int | None = None
) -> dict[str, Any]:
    if speed is not None and speed <= 0:
        raise ConfigError(f"--speed must be positive, got {speed:g}")
    # One pass first: validates the file and finds its topics before anything starts.
    times, topics = [], set()
    for rec in read_mcap(path):
        times.append(rec.t)
        topics.add(rec.topic)
    runtime = Runtime(SimClock(speed=speed))
    ros = None
    if ros2:
        from amiro.ros2.bridge import Ros2Bridge
        from amiro.ros2.context import RosContext

        ros = RosContext("amiro_replay", domain_id)
        runtime.add(Ros2Bridge(ros, publish=sorted(topics)))
    replayer = runtime.add(McapReplayer(path))
    runtime.start()
    span = (max(times) - min(times)) if times else 0.0
    runtime.spin_until(lambda: replayer.finished, span + 1.0)
    runtime.spin_for(0.1)
    runtime.stop()
    if ros is not None:
        ros.close()
    return {
        "file": str(path),
        "messages": sum(replayer.counts.values()),
        "topics": dict(sorted(replayer.counts.items())),
        "skipped": replayer.skipped,
        "duration_s": round(span, 3),
    }
