"""RecognizeActivity's section-5 reframing: backwards when too close, forwards when too far,
still when blocked, and an early give-up when the skeleton stays incomplete."""

import math

import numpy as np

import amiro.behavior.tasks  # noqa: F401 - registers the task types
from amiro.activity.ports import ActivityReading
from amiro.behavior.engine import BehaviorEngine, EngineConfig, GraphRun
from amiro.behavior.graph import TaskGraph
from amiro.behavior.modules import Modules
from amiro.behavior.task import make_task
from amiro.core.clock import SimClock
from amiro.core.messages import Pose2D
from amiro.core.runtime import Runtime
from amiro.navigation.config import NavigationConfig
from amiro.sim.config import PoseSpec, ResidentSpec, SimConfig
from amiro.sim.simulator import Simulation, build_sim
from amiro.sim.skeletons import SkeletonCamera
from amiro.system import add_motion

PERSON_X = 7.08


class FramedRecognizer:
    """Real framing from the simulated camera; the label only inside the trained framing
    (``complete=False``: never a usable skeleton)."""

    def __init__(self, camera: SkeletonCamera, box_range: tuple[float, float], complete: bool):
        self.camera = camera
        self.box_range = box_range
        self.complete = complete

    def observe(self, person: str) -> ActivityReading:
        framing = self.camera.framing(person)
        if framing is None or not self.complete:
            return ActivityReading(None, 0.0, False, None if framing is None else framing[0])
        box, clipped = framing
        framed = self.box_range[0] <= box <= self.box_range[1] and not clipped
        label = "drink_water" if framed else "typing"
        return ActivityReading(label, 0.9, True, box, clipped)


class Odometry:
    def __init__(self, sim: Simulation) -> None:
        self.sim = sim

    @property
    def pose(self) -> Pose2D:
        return self.sim.robot.true_pose

    @property
    def velocity(self) -> tuple[float, float, float]:
        return self.sim.robot.base.velocity


def _recognise(
    distance: float, box_range: tuple[float, float], complete: bool = True
) -> tuple[GraphRun, float]:
    runtime = Runtime(SimClock(), seed=0)
    resident = ResidentSpec(name="maria", pose=PoseSpec(x=PERSON_X, y=2.0, theta=math.pi))
    cfg = SimConfig(start=PoseSpec(x=PERSON_X - distance, y=2.0), residents=[resident])
    sim = build_sim(runtime, cfg)
    recognizer = FramedRecognizer(
        SkeletonCamera(sim, np.random.default_rng(0)), box_range, complete
    )
    modules = Modules(activity=recognizer, navigation=Odometry(sim), world=sim.world)
    add_motion(runtime, NavigationConfig())  # the forward action the reframing drives with
    engine = runtime.add(BehaviorEngine(config=EngineConfig(), modules=modules))
    runtime.start()
    params = {"person": "maria", "timeout_s": 20, "max_reframe_m": 2.0}
    run = engine.submit(TaskGraph("watch", 1).add("rec", make_task("RecognizeActivity", params)))
    runtime.spin_until(lambda: run.done, 40.0)
    return run, PERSON_X - sim.robot.true_pose.x


def test_too_close_the_robot_backs_off_until_the_person_is_framed() -> None:
    run, distance = _recognise(2.0, (0.45, 0.85))
    assert run.outcome == "completed"
    detail = run.records[-1].detail
    assert detail["reframed_m"] > 0.8 and 3.0 < distance < 3.6
    assert abs(detail["reframed_m"] - (distance - 2.0)) < 0.05  # measured, not commanded


def test_too_far_the_robot_moves_closer() -> None:
    run, distance = _recognise(3.5, (0.68, 0.85))
    assert run.outcome == "completed"
    assert run.records[-1].detail["reframed_m"] > 0.1 and distance < 3.4


def test_a_blocked_base_stays_put_and_recognition_times_out() -> None:
    run, distance = _recognise(3.5, (0.3, 0.5))  # wants to back off, a wall behind
    assert run.outcome == "failed"
    detail = run.records[-1].detail
    assert detail["reason"] == "not_recognised" and detail["reframed_m"] == 0.0
    assert abs(distance - 3.5) < 0.02


def test_an_incomplete_skeleton_gives_up_early_for_a_spoken_confirmation() -> None:
    run, _ = _recognise(3.4, (0.45, 0.85), complete=False)
    record = run.records[-1]
    assert run.outcome == "failed" and record.detail["reason"] == "skeleton_incomplete"
    assert record.end_s - record.start_s < 11.0  # incomplete_timeout_s, not timeout_s
