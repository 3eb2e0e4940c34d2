"""`amiro sim --ros2` as a robot driver in a subprocess, shared by the robot and ROS 2 tests."""

from __future__ import annotations

import json
import signal
import subprocess
from pathlib import Path
from typing import Any


def stop_sim(sim: subprocess.Popen[str], tmp_path: Path) -> dict[str, Any]:
    """SIGTERM the simulator, check it ended cleanly, and return its JSON report."""
    sim.send_signal(signal.SIGTERM)
    _, err = sim.communicate(timeout=30)
    assert sim.returncode == 0, err[-2000:]
    report: dict[str, Any] = json.loads((tmp_path / "sim.json").read_text())
    return report
