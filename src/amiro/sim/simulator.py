"""The simulator on the bus: the robot (base, odometry, lidar, head) and the residents.

Topics (all in SI units, REP-105 frames):

``SimRobotNode``
    subscribes ``/cmd_vel`` (Twist, robot frame), ``/amiro/head/cmd`` (JointState with
    HeadYaw/HeadPitch targets), ``/amiro/emergency_stop`` (String, as every robot adapter:
    it stops the base at once, whatever ``/cmd_vel`` says, until released);
    publishes ``/odom`` (Odometry, odom -> base_footprint, drifting) and ``/tf``
    (TransformStamped) at the physics rate, ``/scan`` (LaserScan, ``laser``) at the lidar
    rate, ``/joint_states`` (JointState), ``/amiro/sim/ground_truth`` (Pose2D, map frame)
    and ``/amiro/sim/collision`` (Collision, once per new contact).
``SimResidentsNode``
    subscribes ``/amiro/say`` (SpeechRequest: its ``act`` is the prompt kind, its
    ``addressee`` the resident spoken to, if any); publishes
    ``/amiro/speech/heard`` (SpeechHeard with the ground-truth intent) after each
    resident's scripted delay, only from residents within hearing range of the robot.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import partial

import numpy as np

from amiro.core import names
from amiro.core.config import ConfigError
from amiro.core.messages import (
    CameraInfo,
    Header,
    JointState,
    LaserScan,
    Odometry,
    Pose2D,
    SpeechHeard,
    SpeechRequest,
    String,
    TransformStamped,
    Twist,
    Vector3,
)
from amiro.core.node import Node
from amiro.core.runtime import Runtime
from amiro.core.safety import estop_engaged
from amiro.dialogue.output import speaking_time
from amiro.home.world import World, default_home_path
from amiro.robot.camera import Camera, CameraObservation, CameraParams
from amiro.sim.base import BaseLimits, DriftParams, OmniBase
from amiro.sim.base import Odometry as OdometryModel
from amiro.sim.camera import Head, observe_residents
from amiro.sim.config import ResidentSpec, SimConfig
from amiro.sim.door_help import DOOR_OPENING_S, OPEN_DOOR_REQUEST, open_nearest_door
from amiro.sim.lidar import Lidar, LidarParams
from amiro.sim.messages import Collision
from amiro.sim.residents import DRINK_DURATION, Reply, Resident, ScriptedReply

HEAD_JOINTS = (names.HEAD_YAW, names.HEAD_PITCH)


class SimRobotNode(Node):
    """Pepper's body in the simulated home: physics at a fixed rate, sensors on timers."""

    def __init__(
        self,
        world: World,
        base: OmniBase,
        lidar: Lidar,
        head: Head,
        rng: np.random.Generator,
        physics_rate: float = 20.0,
        cmd_timeout: float = 0.5,
        name: str = "sim_robot",
    ) -> None:
        super().__init__(name)
        self.world = world
        self.base = base
        self.lidar = lidar
        self.head = head
        self.rng = rng
        self.physics_rate = physics_rate
        self.cmd_timeout = cmd_timeout
        self.estop = False
        self.steps = 0
        self.last_scan: LaserScan | None = None
        self._last_cmd = -math.inf

    # --- accessors for oracles and tests ----------------------------------------------
    @property
    def true_pose(self) -> Pose2D:
        return self.base.pose

    @property
    def odom_pose(self) -> Pose2D:
        return self.base.odometry.pose if self.base.odometry is not None else self.base.pose

    @property
    def head_yaw(self) -> float:
        return self.head.yaw

    @property
    def head_pitch(self) -> float:
        return self.head.pitch

    @property
    def collisions(self) -> int:
        return self.base.collisions

    # --- lifecycle ----------------------------------------------------------------------
    def on_start(self) -> None:
        self.base.stop()
        self._last_cmd = -math.inf
        self.create_subscription(names.CMD_VEL, Twist, self._on_cmd_vel)
        self.create_subscription(names.HEAD_CMD, JointState, self._on_head_cmd)
        self.create_subscription(names.EMERGENCY_STOP, String, self._on_estop)
        self.pub_odom = self.create_publisher(names.ODOM, Odometry)
        self.pub_tf = self.create_publisher(names.TF, TransformStamped)
        self.pub_scan = self.create_publisher(names.SCAN, LaserScan)
        self.pub_joints = self.create_publisher(names.JOINT_STATES, JointState)
        self.pub_truth = self.create_publisher(names.GROUND_TRUTH, Pose2D)
        self.pub_collision = self.create_publisher(names.COLLISION, Collision)
        self.create_timer(1.0 / self.physics_rate, self._physics)
        self.create_timer(1.0 / self.lidar.params.rate, self._scan)

    def _on_cmd_vel(self, msg: Twist) -> None:
        self._last_cmd = self.now()
        if not self.estop:
            self.base.set_command(msg.linear.x, msg.linear.y, msg.angular.z)

    def _on_head_cmd(self, msg: JointState) -> None:
        targets = dict(zip(msg.name, msg.position, strict=False))
        self.head.command(targets.get(names.HEAD_YAW), targets.get(names.HEAD_PITCH))

    def _on_estop(self, msg: String) -> None:
        self.estop = estop_engaged(msg.data)
        if self.estop:
            self.base.stop()

    # --- timers -------------------------------------------------------------------------
    def _physics(self) -> None:
        now = self.now()
        dt = 1.0 / self.physics_rate
        if self.estop or now - self._last_cmd > self.cmd_timeout:
            self.base.set_command(0.0, 0.0, 0.0)
        if self.base.step(dt, self.world.is_free):
            p = self.base.pose
            self.pub_collision.publish(Collision(now, p.x, p.y, p.theta, self.base.collisions))
        self.head.step(dt)
        self.steps += 1
        self._publish_state(now)

    def _publish_state(self, now: float) -> None:
        odom = self.odom_pose
        vx, vy, wz = self.base.velocity
        self.pub_odom.publish(
            Odometry(
                Header(now, "odom"), "base_footprint", odom.to_pose(), Twist.planar(vx, vy, wz)
            )
        )
        q = odom.to_pose().orientation
        self.pub_tf.publish(
            TransformStamped(Header(now, "odom"), "base_footprint", Vector3(odom.x, odom.y), q)
        )
        self.pub_joints.publish(
            JointState(Header(now, ""), HEAD_JOINTS, (self.head.yaw, self.head.pitch))
        )
        self.pub_truth.publish(self.base.pose)

    def _scan(self) -> None:
        self.last_scan = self.lidar.scan(self.world.live, self.base.pose, self.now(), self.rng)
        self.pub_scan.publish(self.last_scan)


class SimResidentsNode(Node):
    """The people at home: they answer the robot per their scripts and act in time."""

    UPDATE_PERIOD = 0.1

    def __init__(
        self,
        world: World,
        robot: SimRobotNode,
        camera: Camera,
        residents: list[Resident],
        rng: np.random.Generator,
        hearing_range: float = 3.0,
        residents_block: bool = True,
        name: str = "sim_residents",
    ) -> None:
        super().__init__(name)
        self.world = world
        self.robot = robot
        self.camera = camera
        self.residents: dict[str, Resident] = {r.name: r for r in residents}
        self.rng = rng
        self.hearing_range = hearing_range
        self.residents_block = residents_block
        self.replies: list[Reply] = []  # every reply sent, for tests and reports
        self.sync_obstacles()

    def on_start(self) -> None:
        self.create_subscription(names.SAY, SpeechRequest, self._on_say)
        self.pub_heard = self.create_publisher(names.HEARD, SpeechHeard)
        self.create_timer(self.UPDATE_PERIOD, self._update)

    # --- accessors ----------------------------------------------------------------------
    def observe(self) -> list[CameraObservation]:
        """What the head camera sees right now."""
        return observe_residents(
            self.camera,
            self.world,
            self.robot.true_pose,
            self.robot.head_yaw,
            self.robot.head_pitch,
            self.residents.values(),
            self.rng,
        )

    def move(
        self,
        name: str,
        x: float,
        y: float,
        heading: float | None = None,
        posture: str | None = None,
    ) -> None:
        """Teleport a resident (scenario scripting); keeps the world obstacles in sync."""
        r = self.residents[name]
        r.x, r.y = x, y
        if heading is not None:
            r.heading = heading
        if posture is not None:
            r.posture = posture  # type: ignore[assignment]
            r.__post_init__()
        self.sync_obstacles()

    def set_present(self, name: str, present: bool) -> None:
        self.residents[name].present = present
        self.sync_obstacles()

    def sync_obstacles(self) -> None:
        """Standing residents are 0.4 m squares the lidar sees and the base bumps into."""
        for r in self.residents.values():
            key = f"resident:{r.name}"
            if self.residents_block and r.present and r.posture == "standing":
                h = 0.2
                poly = [
                    (r.x - h, r.y - h),
                    (r.x + h, r.y - h),
                    (r.x + h, r.y + h),
                    (r.x - h, r.y + h),
                ]
                if self.world.obstacles.get(key, ([], 0.0))[0] != poly:
                    self.world.add_obstacle(key, poly, r.body.z_max)
            else:
                self.world.remove_obstacle(key)

    # --- dialogue -----------------------------------------------------------------------
    def _on_say(self, msg: SpeechRequest) -> None:
        kind, target = msg.act or "default", msg.addressee
        robot = self.robot.true_pose
        near = [
            r
            for r in self.residents.values()
            if r.present
            and r.distance_to(robot.x, robot.y) <= self.hearing_range
            and (not target or r.name == target)
        ]
        if not near:
            return
        resident = min(near, key=lambda r: r.distance_to(robot.x, robot.y))
        reply = resident.reply_to(kind, self.rng)
        if reply is None:
            return
        # People answer once the robot has finished speaking.
        self.call_later(speaking_time(msg.text) + reply.delay, partial(self._deliver, reply))

    def _deliver(self, reply: Reply) -> None:
        resident = self.residents[reply.resident]
        self.replies.append(reply)
        self.pub_heard.publish(
            SpeechHeard(reply.text, reply.lang, speaker=reply.resident, intent=reply.intent)
        )
        if reply.prompt == "hydration_reminder" and reply.reply == "confirm":
            resident.start_activity("drink_water", self.now(), DRINK_DURATION)
        if reply.prompt == OPEN_DOOR_REQUEST and reply.reply == "confirm":
            self.call_later(DOOR_OPENING_S, partial(open_nearest_door, self.world, resident))

    def _update(self) -> None:
        now = self.now()
        for r in self.residents.values():
            r.update(now)


@dataclass
class Simulation:
    """Everything :func:`build_sim` made, for oracles, scenarios and tests."""

    config: SimConfig
    world: World
    robot: SimRobotNode
    residents: SimResidentsNode

    # --- the head camera (see amiro.robot.camera.HeadCamera) -------------------------------
    def now(self) -> float:
        return self.robot.now()

    def observe(self) -> list[CameraObservation]:
        return self.residents.observe()

    def head_joints(self) -> tuple[float, float]:
        return self.robot.head_yaw, self.robot.head_pitch

    def camera_info(self) -> CameraInfo:
        return self.residents.camera.info(self.now())

    def camera_mount(self) -> tuple[float, float]:
        params = self.residents.camera.params
        return params.height, params.forward

    def robot_pose(self) -> Pose2D:
        return self.robot.true_pose

    def household(self) -> tuple[str, ...]:
        return tuple(r.name for r in self.config.residents)


def make_resident(spec: ResidentSpec, world: World) -> Resident:
    if spec.pose is not None:
        x, y, th = spec.pose.x, spec.pose.y, spec.pose.theta
    else:
        assert spec.at is not None
        p = world.spot(spec.at)
        x, y, th = p.x, p.y, p.theta
    script = {
        kind: [
            ScriptedReply(s.reply, s.delay) for s in (steps if isinstance(steps, list) else [steps])
        ]
        for kind, steps in spec.script.items()
    }
    return Resident(
        name=spec.name,
        x=x,
        y=y,
        heading=th,
        language=spec.language,
        posture=spec.posture,
        activity=spec.activity,
        present=spec.present,
        skeleton_occluded=spec.skeleton_occluded,
        script=script,
    )


def build_sim(runtime: Runtime, config: SimConfig | None = None) -> Simulation:
    """Create the world and the simulator nodes and add them to ``runtime``.

    Randomness comes from independent children of ``runtime.rng``, so a seed replays a run.
    """
    cfg = config or SimConfig()
    world = World.load(cfg.home or default_home_path(), cfg.resolution)
    try:
        for door, is_open in cfg.doors.items():
            world.set_door(door, is_open)
        for ob in cfg.obstacles:
            world.add_obstacle(ob.name, list(ob.polygon), ob.height)
        if isinstance(cfg.start, str):
            start = world.spot(cfg.start)
        else:
            start = Pose2D(cfg.start.x, cfg.start.y, cfg.start.theta)
        people = [make_resident(r, world) for r in cfg.residents]
    except (KeyError, ValueError) as exc:
        raise ConfigError(f"sim: {exc.args[0] if exc.args else exc}") from None
    rng_odom, rng_lidar, rng_people = runtime.rng.spawn(3)
    b, o, li, c = cfg.base, cfg.odometry, cfg.lidar, cfg.camera
    base = OmniBase(
        start,
        BaseLimits(b.max_linear, b.max_angular, b.max_linear_accel, b.max_angular_accel, b.radius),
        OdometryModel(rng_odom, DriftParams(**o.model_dump())),
    )
    lidar = Lidar(LidarParams(li.beams, li.range_min, li.range_max, li.rate, li.noise))
    camera = Camera(
        CameraParams(
            height=c.height,
            width=c.width,
            image_height=c.image_height,
            hfov_deg=c.hfov_deg,
            vfov_deg=c.vfov_deg,
            depth_sigma=c.depth_sigma,
            max_range=c.max_range,
        )
    )
    robot = SimRobotNode(
        world, base, lidar, Head(c.head_speed), rng_lidar, cfg.physics_rate, b.cmd_timeout
    )
    residents = SimResidentsNode(
        world,
        robot,
        camera,
        people,
        rng_people,
        cfg.hearing_range,
        cfg.residents_block,
    )
    runtime.add(robot)
    runtime.add(residents)
    return Simulation(cfg, world, robot, residents)
