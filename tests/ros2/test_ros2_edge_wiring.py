"""The edge builds the embedded system's real perception and activity modules from the shared
builders, and the bridged topics they need cross with their codecs."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from amiro.activity.recognizer import SkeletonActivityRecognizer
from amiro.behavior.engine import BehaviorEngine
from amiro.core import names
from amiro.core.clock import SimClock
from amiro.core.messages import Header, Skeleton
from amiro.core.runtime import Runtime
from amiro.deploy.config import DEFAULT_PUBLISH, DEFAULT_SUBSCRIBE, NodeConfig
from amiro.deploy.dialogue import RemoteUnderstanding
from amiro.deploy.roles import build_edge_role
from amiro.dialogue.oracle import OracleUnderstanding
from amiro.dialogue.understanding import Nlu
from amiro.perception.stack import SimPeopleFinder
from amiro.ros2.routes import route
from amiro.ros2.types import RosbagsTypes
from amiro.scenarios.hydration import HydrationOptions, scenario_config
from amiro.sim.activity_oracle import OracleActivityRecognizer
from amiro.sim.perception_oracle import OraclePeopleFinder
from amiro.system import SystemConfig

HEAD_TOPICS = {names.OBSERVATIONS, names.SKELETONS, "/camera/camera_info", "/joint_states"}


def _edge(cfg: SystemConfig) -> tuple[Runtime, dict[str, Any]]:
    runtime = Runtime(SimClock(), seed=1)
    parts = build_edge_role(runtime, "edge", NodeConfig(role="edge"), cfg)
    engine = runtime.node("behavior")
    assert isinstance(engine, BehaviorEngine)
    return runtime, {**vars(engine.modules), "summary": parts.summary()}


def test_the_edge_runs_the_real_modules_by_default() -> None:
    runtime, modules = _edge(scenario_config(HydrationOptions(seed=1)))
    assert isinstance(modules["perception"], SimPeopleFinder)
    assert isinstance(modules["activity"], SkeletonActivityRecognizer)
    summary = modules["summary"]
    assert summary["perception"] == "sim-detector" and summary["activity"] == "onnx"
    assert summary["people_estimates"] == 0
    assert set(runtime.nodes) >= {"fall_monitor", "notifications"}
    assert isinstance(modules["nlu"], Nlu)  # replies understood by the household's NLU


def test_listen_asks_the_cloud_when_it_serves_understanding() -> None:
    runtime = Runtime(SimClock(), seed=1)
    node = NodeConfig(role="edge", call_services=(names.UNDERSTAND,))
    build_edge_role(runtime, "edge", node, scenario_config(HydrationOptions(seed=1)))
    engine = runtime.node("behavior")
    assert isinstance(engine, BehaviorEngine)
    assert isinstance(engine.modules.nlu, RemoteUnderstanding)


def test_oracles_run_on_the_edge_only_when_configured() -> None:
    cfg = SystemConfig.model_validate(
        {"perception": {"backend": "oracle"}, "activity": {"backend": "oracle"}}
    )
    _, modules = _edge(cfg)
    assert isinstance(modules["perception"], OraclePeopleFinder)
    assert isinstance(modules["activity"], OracleActivityRecognizer)
    assert modules["summary"]["perception"] == "oracle"
    oracle_nlu = SystemConfig.model_validate({"dialogue": {"nlu": "oracle"}})
    assert isinstance(_edge(oracle_nlu)[1]["nlu"], OracleUnderstanding)


def test_the_robot_publishes_and_the_edge_hears_what_the_modules_read() -> None:
    assert set(DEFAULT_PUBLISH["sim"]) >= HEAD_TOPICS
    assert set(DEFAULT_SUBSCRIBE["edge"]) >= HEAD_TOPICS


def test_a_skeleton_crosses_as_json_with_its_untracked_joints() -> None:
    types = RosbagsTypes()
    codec = route(names.SKELETONS).codec
    joints = np.random.default_rng(0).normal(size=(25, 3))
    tracked = np.ones(25, dtype=bool)
    tracked[[3, 7]] = False
    sent = Skeleton(Header(4.25, "camera_level"), 1, joints, tracked)
    raw = types.store.serialize_cdr(codec.encode(types, sent, 5.0), codec.ros_type)
    got = codec.decode(types.store.deserialize_cdr(raw, codec.ros_type))
    assert got.header == sent.header and got.body_id == 1
    assert np.array_equal(got.tracked, tracked)
    assert np.allclose(got.joints[tracked], joints[tracked], atol=1e-5)


@pytest.mark.parametrize(
    "data",
    ['{"stamp": 1}', "[1, 2]", '{"stamp": 1, "frame_id": "", "body_id": 0, '
     '"joints": [0, 0, 0], "tracked": [true]}'],
)  # fmt: skip
def test_a_malformed_skeleton_is_rejected_with_value_error(data: str) -> None:
    types = RosbagsTypes()
    with pytest.raises(ValueError):
        route(names.SKELETONS).codec.decode(types.make("std_msgs/msg/String", data=data))
