"""Search side-steps when the face is backlit (the paper's proposed fix), then finds her."""

from __future__ import annotations

import math

import numpy as np

from amiro.behavior.loader import load_behavior_data
from amiro.perception.config import PerceptionConfig
from amiro.perception.stack import build_people_finder
from amiro.system import SystemConfig, build_system

SEARCH_ONLY = {
    "name": "find",
    "priority": 1,
    "blackboard": {},
    "entry": "search",
    "tasks": {"search": {"type": "Search", "params": {"person": "maria"}}},
}


def run_search(side_steps: int) -> dict[str, object]:
    # Maria sits on the couch in front of the living-room window, facing the robot: backlit.
    cfg = SystemConfig.model_validate(
        {
            "seed": 5,
            "sim": {
                "start": {"x": 7.0, "y": 2.6, "theta": -math.pi / 2},
                "residents": [
                    {
                        "name": "maria",
                        "pose": {"x": 7.0, "y": 0.6, "theta": math.pi / 2},
                        "posture": "sitting_couch",
                    }
                ],
            },
        }
    )
    system = build_system(cfg)
    system.engine.modules.perception = build_people_finder(
        system.sim, np.random.default_rng(5), PerceptionConfig()
    )
    system.start()
    data = {
        **SEARCH_ONLY,
        "tasks": {
            "search": {"type": "Search", "params": {"person": "maria", "side_steps": side_steps}}
        },
    }
    run = system.engine.submit(load_behavior_data(data))
    system.runtime.spin_until(lambda: run.done, 120.0)
    detail: dict[str, object] = dict(run.records[-1].detail)
    detail["side_stepped"] = (
        system.sim.robot.true_pose.distance_to(type(system.sim.robot.true_pose)(7.0, 2.6, 0.0))
        > 0.5
    )
    detail["result"] = run.records[-1].result
    return detail


def test_without_side_steps_the_backlit_face_is_never_recognised() -> None:
    assert run_search(side_steps=0)["result"] == "failure"


def test_backlit_face_side_step_then_found() -> None:
    detail = run_search(side_steps=2)
    assert detail["result"] == "success" and detail["side_stepped"]
    position = detail["position"]
    assert isinstance(position, list | tuple)
    x, y = (float(v) for v in position)
    assert math.hypot(x - 7.0, y - 0.6) < 0.3
