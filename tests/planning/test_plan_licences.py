"""The default engine is Apache-licensed: GPL engines load only when config chooses them."""

from __future__ import annotations

import subprocess
import sys

import pytest
from up_kairos.writer import KairosWriter  # type: ignore[import-untyped]

from amiro.behavior.planning.config import PlanningConfig
from amiro.behavior.planning.domain import home_domain
from amiro.behavior.planning.kairos_engine import WrittenProblem
from amiro.behavior.planning.knowledge import DoorState, KnowledgeBase
from amiro.behavior.planning.planner import HomePlanner
from amiro.behavior.planning.problem import Goal, RobotState, make_problem
from amiro.behavior.planning.topology import topology_from_world
from amiro.core.config import ConfigError
from amiro.home.world import World, default_home_path

DEFAULT_PLANNING_PATH = """
import sys
from amiro.behavior.planning import HomePlanner, KnowledgeBase, PlanningConfig, Goal, RobotState
from amiro.behavior.planning import topology_from_world
from amiro.scenarios.deliver_notification import DeliveryOptions
from amiro.home.world import World, default_home_path

kb = KnowledgeBase(topology_from_world(World.load(default_home_path())), {"maria": "living_room"})
config = PlanningConfig(engine=DeliveryOptions().engine)
outcome = HomePlanner(config).plan(kb, RobotState("hallway", 0.8, 1.0), [Goal("notified", "maria")])
assert outcome.solved, outcome.explanation
print(config.engine, sorted(m for m in ("pyperplan", "up_pyperplan", "up_fast_downward")
                            if m in sys.modules))
"""


def test_default_planning_loads_no_gpl_package() -> None:
    out = subprocess.run(
        [sys.executable, "-c", DEFAULT_PLANNING_PATH],
        capture_output=True,
        text=True,
        check=True,
        timeout=120,
    ).stdout
    assert out.split() == ["kairos", "[]"]


@pytest.mark.parametrize(
    ("engine", "package"), [("pyperplan", "up_pyperplan"), ("fast-downward", "up_fast_downward")]
)
def test_missing_gpl_engine_names_the_extra(
    monkeypatch: pytest.MonkeyPatch, engine: str, package: str
) -> None:
    monkeypatch.setitem(sys.modules, package, None)  # as if not installed
    with pytest.raises(ConfigError, match=r"pip install 'amiro\[planners-gpl\]'") as err:
        HomePlanner(PlanningConfig(engine=engine))
    assert "\n" not in str(err.value)


@pytest.mark.parametrize("temporal", [False, True])
def test_written_problem_gives_the_same_pddl(temporal: bool) -> None:
    kb = KnowledgeBase(
        topology_from_world(World.load(default_home_path())),
        {"maria": "living_room", "john": "hallway"},
    )
    kb.set_door("living_door", DoorState.CLOSED, 1.0, "lidar")
    problem = make_problem(
        home_domain(temporal), kb, RobotState("hallway", 0.8, 1.0), [Goal("notified", "maria")]
    )
    fast = KairosWriter(WrittenProblem(problem))
    full = KairosWriter(problem)
    assert fast.get_domain() == full.get_domain()
    pddl = fast.get_problem()
    assert pddl == full.get_problem()
    assert "(door_closed living_door)" in pddl
    assert ("travel_time" in pddl) == temporal
