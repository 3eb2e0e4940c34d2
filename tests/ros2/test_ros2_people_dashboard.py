"""The cloud's dashboard shows the people the edge tracks: the edge publishes its confirmed
tracks on /amiro/people and the cloud's RemoteRobot reports them as the embedded system
does.  Edge and cloud share one bus here; the ROS 2 leg is the route's codec."""

from __future__ import annotations

from amiro.behavior.engine import BehaviorEngine
from amiro.core import names
from amiro.core.clock import SimClock
from amiro.core.messages import Header, People, Person, Point
from amiro.core.runtime import Runtime
from amiro.deploy.behaviors import BehaviorRequests
from amiro.deploy.config import DEFAULT_PUBLISH, DEFAULT_SUBSCRIBE, NodeConfig
from amiro.deploy.people import TrackedPeoplePublisher, dashboard_people
from amiro.deploy.roles import build_edge_role
from amiro.deploy.web_robot import RemoteRobot
from amiro.home.world import World, default_home_path
from amiro.perception.tracking import Measurement, PeopleTracker
from amiro.ros2.routes import route
from amiro.ros2.types import RosbagsTypes
from amiro.scenarios.hydration import HydrationOptions, scenario_config
from amiro.system import SystemConfig


def _edge_and_cloud() -> tuple[Runtime, PeopleTracker, RemoteRobot]:
    runtime = Runtime(SimClock())
    tracker = PeopleTracker()
    runtime.add(TrackedPeoplePublisher(tracker, period_s=0.5))
    home = World.load(default_home_path()).home
    robot = runtime.add(RemoteRobot(home, {}, names.LOCALIZATION, runtime.add(BehaviorRequests())))
    runtime.start()
    return runtime, tracker, robot


def test_the_dashboard_shows_the_confirmed_tracks_until_they_are_forgotten() -> None:
    runtime, tracker, robot = _edge_and_cloud()
    assert robot.state()["people"] == []
    tracker.update(0.0, [Measurement(Point(1.234, 2.0, 1.6), 0.9, "maria")])
    tracker.update(0.0, [Measurement(Point(6.0, 1.0, 1.0), 0.5)])  # one hit, no face: not yet
    runtime.spin_for(1.0)
    people = robot.state()["people"]
    assert people == [{"name": "maria", "x": 1.23, "y": 2.0, "activity": ""}]
    tracker.update(
        runtime.clock.now(),
        [Measurement(Point(6.1, 1.0, 1.0), 0.5), Measurement(Point(1.3, 2.0, 1.6), 0.9)],
    )  # the stranger seen twice now; an unnamed track shows its id as the embedded one does
    runtime.spin_for(1.0)
    names = sorted(p["name"] for p in robot.state()["people"])
    assert names == ["maria", "person_2"]
    runtime.spin_for(tracker.cfg.forget_s + 1.0)  # nobody looked since
    assert robot.state()["people"] == []


def test_people_cross_ros2_as_json_with_names_and_positions() -> None:
    types = RosbagsTypes()
    codec = route(names.PEOPLE).codec
    sent = People(
        Header(3.5, "map"),
        (Person("person_1", "maria", Point(1.0, 2.0, 1.6), 0.9),
         Person("person_2", None, Point(4.0, 0.5, 1.0), 0.6)),
    )  # fmt: skip
    raw = types.store.serialize_cdr(codec.encode(types, sent, 4.0), codec.ros_type)
    got = codec.decode(types.store.deserialize_cdr(raw, codec.ros_type))
    assert got == sent
    assert [p["name"] for p in dashboard_people(got)] == ["maria", "person_2"]


def test_the_edge_publishes_its_perception_tracks_and_the_cloud_hears_them() -> None:
    assert names.PEOPLE in DEFAULT_PUBLISH["edge"] and names.PEOPLE in DEFAULT_SUBSCRIBE["cloud"]
    runtime = Runtime(SimClock(), seed=1)
    build_edge_role(runtime, "edge", NodeConfig(role="edge"), scenario_config(HydrationOptions()))
    publisher, engine = runtime.node("tracked_people"), runtime.node("behavior")
    assert isinstance(publisher, TrackedPeoplePublisher) and isinstance(engine, BehaviorEngine)
    assert publisher.tracker is engine.modules.perception.tracker


def test_an_edge_without_a_tracker_publishes_no_people() -> None:
    runtime = Runtime(SimClock(), seed=1)
    oracle = SystemConfig.model_validate({"perception": {"backend": "oracle"}})
    build_edge_role(runtime, "edge", NodeConfig(role="edge"), oracle)
    assert "tracked_people" not in runtime.nodes
