"""People on ROS4HRI (REP-155): a plain rclpy subscriber sees the resident amiro's perception
tracks, and ROS4HRI from another stack comes back onto amiro's bus."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest
from numpy.random import default_rng as rng

from amiro.core import names, registry
from amiro.core.clock import SimClock
from amiro.core.config import ConfigError
from amiro.core.messages import Header, People, Person, Point
from amiro.core.runtime import Runtime
from amiro.deploy.people import TrackedPeoplePublisher, finder_tracker
from amiro.perception.config import PerceptionConfig
from amiro.perception.stack import PerceptionInputs
from amiro.ros2.bridge import Ros2Bridge
from amiro.ros2.context import RosContext
from amiro.ros2.env import ros_environment
from amiro.ros2.hri import HriListener, HriPublisher
from amiro.scenarios.hydration import HydrationOptions, scenario_config
from amiro.system import build_system
from amiro.web.robot import single_task_graph

SCRIPT = Path(__file__).parent / "scripts" / "listen_hri.py"


@pytest.mark.slow
def test_a_plain_subscriber_sees_the_resident_in_view(domain_id: int) -> None:
    ros = RosContext("amiro_test_hri", domain_id)
    system = build_system(scenario_config(HydrationOptions()), SimClock(speed=4.0))
    tracker = finder_tracker(system.engine.modules.perception)
    assert tracker is not None
    runtime = system.runtime
    runtime.add(Ros2Bridge(ros))  # pumps ROS 2
    runtime.add(TrackedPeoplePublisher(tracker, period_s=0.5))
    hri = runtime.add(HriPublisher(ros))
    resident = system.people()[0].name
    listener = subprocess.Popen(
        [sys.executable, str(SCRIPT), "180"],
        env={**os.environ, **ros_environment(domain_id)},
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    system.start()
    try:
        system.engine.submit(single_task_graph("Search", {"person": resident}, 1))
        deadline = time.monotonic() + 240.0
        while listener.poll() is None and time.monotonic() < deadline:
            runtime.spin_for(0.05)
        truth = {p.name: (p.x, p.y) for p in system.people()}
    finally:
        system.stop()
        ros.close()
        out, err = listener.communicate(timeout=30)
    assert listener.returncode == 0, err
    seen = json.loads(out.strip().splitlines()[-1])
    assert hri.published > 0
    assert resident in seen["persons"]  # her id is her recognised name
    person = seen["people"][resident]
    assert person["name"] == resident and 0.0 < person["location_confidence"] <= 1.0
    body = f"body_{person['face_id']}"
    assert person["face_id"] in seen["bodies"] and body in seen["frames"]
    parent, x, y, _z = seen["frames"][f"person_{resident}"]
    assert parent == "map"
    error_m = math.dist((x, y), truth[resident])
    print(f"person_{resident} frame {error_m:.3f} m from her true position")
    assert error_m < 0.3


def test_ros4hri_from_another_stack_reaches_the_bus(domain_id: int) -> None:
    """amiro's own publisher stands in for the other stack: what one side says, the other
    side's listener puts back on its bus, names, positions and confidences intact."""
    a, b = RosContext("amiro_test_hri_a", domain_id), RosContext("amiro_test_hri_b", domain_id)
    talker, hearer = Runtime(SimClock(speed=1.0)), Runtime(SimClock(speed=1.0))
    talker.add(Ros2Bridge(a))
    talker.add(HriPublisher(a))
    hearer.add(Ros2Bridge(b))
    hearer.add(HriListener(b, topic=names.HRI_PEOPLE))
    heard: list[People] = []
    hearer.bus.subscribe(names.HRI_PEOPLE, People, heard.append, depth=100)
    # perception.backend: hri, as the edge builds it: the people the other stack tracks
    cfg = PerceptionConfig(backend="hri")
    finder = registry.create("perception", "hri", PerceptionInputs(cfg, rng(), bus=hearer.bus))
    talker.start()
    hearer.start()
    sent = People(
        Header(1.0, "map"),
        (
            Person("t7", "Maria", Point(2.5, 1.0, 1.1), 0.8),
            Person("t9", None, Point(6.0, 3.0, 1.0), 0.4),
        ),
    )
    try:
        deadline = time.monotonic() + 60.0
        while (
            not (
                heard
                and len(heard[-1].people) == 2
                and all(p.name or p.id == "t9" for p in heard[-1].people)
            )
            and time.monotonic() < deadline
        ):
            talker.bus.publish(names.PEOPLE, sent)
            talker.spin_for(0.1)
            hearer.spin_for(0.1)
    finally:
        talker.stop()
        hearer.stop()
        a.close()
        b.close()
    got = {p.id: p for p in heard[-1].people}
    assert sorted(got) == ["maria", "t9"]
    assert got["maria"].name == "Maria" and got["t9"].name is None
    assert (got["maria"].position.x, got["maria"].position.y) == (2.5, 1.0)
    assert math.isclose(got["maria"].confidence, 0.8, rel_tol=1e-6)
    seen = {p.track_id: p for p in finder.look()}
    assert seen["maria"].name == "Maria" and seen["t9"].name is None
    assert (seen["maria"].position.x, seen["maria"].position.y) == (2.5, 1.0)
    with pytest.raises(ConfigError, match="hri reads ROS4HRI"):
        registry.create("perception", "hri", PerceptionInputs(cfg, rng()))
