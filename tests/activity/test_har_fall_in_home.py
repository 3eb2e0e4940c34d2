"""A resident falls in the simulated home: the shipped model on the simulated skeleton
stream sees it, and the fall behaviour preempts what the robot was doing."""

import math

from amiro.behavior.loader import load_behavior_data
from amiro.scenarios.hydration import HydrationOptions, scenario_config
from amiro.system import SystemConfig, build_system

COUCH = (6.5, 0.61)
ROBOT = (3.6, 1.6)


def test_a_fall_in_view_preempts_the_running_behaviour() -> None:
    data = scenario_config(HydrationOptions(seed=1)).model_dump()
    data["environment"]["rules"] = []  # no hydration reminder: the robot just waits
    heading = math.atan2(COUCH[1] - ROBOT[1], COUCH[0] - ROBOT[0])
    data["sim"]["start"] = {"x": ROBOT[0], "y": ROBOT[1], "theta": heading}
    system = build_system(SystemConfig.model_validate(data))
    system.start()
    runtime, engine = system.runtime, system.engine
    chore = {
        "name": "chore",
        "priority": 1,
        "entry": "wait",
        "tasks": {"wait": {"type": "Wait", "params": {"seconds": 60}}},
    }
    engine.submit(load_behavior_data(chore))
    runtime.spin_for(5.0)
    assert [r.name for r in engine.runs.values()] == ["chore"]  # sitting with a phone
    system.sim.residents.residents["maria"].start_activity("falling", runtime.clock.now())
    runtime.spin_until(lambda: "fall" in {r.name for r in engine.runs.values()}, 10.0)
    runtime.spin_for(0.2)
    current = engine.current()
    assert current is not None and current["name"] == "fall"
    fall = next(r for r in engine.runs.values() if r.name == "fall")
    assert fall.blackboard["person"] == "maria"
