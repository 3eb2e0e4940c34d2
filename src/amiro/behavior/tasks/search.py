"""Search: look for a named person by turning the head, then the base, then other rooms.

Perception is always on (paper, section 3): the person may be recognised at any moment,
including while the robot drives between rooms.  The person's map position and room go to
the blackboard as ``person_position`` and ``person_room`` for the MoveTo that follows.

Beyond the paper: when someone is seen whose face is backlit (the camera faces a light
source), the robot side-steps across its line of sight to change the viewing angle and looks
again, as the paper proposes, before carrying on with the search.
"""

from __future__ import annotations

import math
from collections import deque
from typing import Any

from pydantic import Field

from amiro.behavior.task import Task, TaskContext, TaskParams, TaskStatus
from amiro.behavior.tasks.gaze import look_at, point_head
from amiro.core import names
from amiro.core.bus import GoalHandle
from amiro.core.messages import Point, Pose2D
from amiro.navigation.move_to import MoveToGoal

HEAD_SWEEP = (0.0, 0.9, -0.9, 1.8, -1.8)  # rad: centre, then wider on each side
SIDE_STEP_M = 1.0  # across the line of sight: about 20-30 degrees at 2-3 m
ROBOT_CLEARANCE_M = 0.35


class Search(Task):
    """params: ``person``; ``dwell_s`` per head position (default 1.2); ``sightings`` needed
    (default 2); ``side_steps`` allowed for backlit faces (default 2).  Fails with
    ``not_found`` after every room has been looked at."""

    type_name = "Search"
    cancellable = True

    class Params(TaskParams):
        person: str
        dwell_s: float = Field(1.2, gt=0)
        sightings: int = Field(2, ge=1)
        side_steps: int = Field(2, ge=0)

    def start(self, ctx: TaskContext) -> None:
        p = self.bind(ctx, self.Params)
        self.person = p.person
        self.dwell = p.dwell_s
        self.needed = p.sightings
        self.side_steps_left = p.side_steps
        self.world = ctx.need(ctx.modules.world, "world")
        self.sightings: list[Point] = []
        self.visited: set[str] = set()
        self.steps: deque[tuple[str, Any]] = deque()
        self.goal: GoalHandle[MoveToGoal, Any, Any] | None = None
        self.step_until = ctx.now()
        self.room = ""  # the room being searched, and the step under way (for feedback)
        self.step = ""
        self._look_around(ctx, turn=True)
        self.detail = {"rooms": []}

    def _pose(self, ctx: TaskContext) -> Pose2D | None:
        pose: Pose2D | None = ctx.need(ctx.modules.navigation, "navigation").pose
        return pose

    def _look_around(self, ctx: TaskContext, turn: bool) -> None:
        pose = self._pose(ctx)
        if pose is not None:
            room = self.world.room_at(pose.x, pose.y)
            if room is not None:
                self.visited.add(room)
                self.room = room
        self.steps.extend(("head", yaw) for yaw in HEAD_SWEEP)
        if turn:
            self.steps.append(("turn", math.pi))
            self.steps.extend(("head", yaw) for yaw in HEAD_SWEEP[1:])
        self.steps.append(("head", 0.0))

    def _next_room(self, ctx: TaskContext) -> str | None:
        pose = self._pose(ctx)
        todo = [r for r in self.world.room_names() if r not in self.visited]
        if not todo or pose is None:
            return None
        return str(min(todo, key=lambda r: pose.distance_to(self.world.place(r))))

    def _start_step(self, ctx: TaskContext) -> bool:
        """Begin the next search step; False when there is nothing left to try."""
        if not self.steps:
            room = self._next_room(ctx)
            if room is None:
                return False
            self.visited.add(room)
            self.room = room
            self.detail["rooms"].append(room)
            ctx.event("search_room", room=room, person=self.person)
            self.steps.append(("goto", room))
        kind, arg = self.steps.popleft()
        self.step = kind
        if kind == "look":
            look_at(ctx, arg)
            self.step_until = ctx.now() + 2 * self.dwell
        elif kind == "head":
            point_head(ctx, float(arg))
            self.step_until = ctx.now() + self.dwell
        elif kind == "turn":
            pose = self._pose(ctx)
            if pose is not None:
                target = Pose2D(pose.x, pose.y, pose.theta + float(arg))
                self.goal = ctx.bus.send_goal(names.MOVE_TO, MoveToGoal(pose=target))
        elif kind == "step":
            point_head(ctx, 0.0)
            self.goal = ctx.bus.send_goal(names.MOVE_TO, MoveToGoal(pose=arg))
        else:
            point_head(ctx, 0.0)
            self.goal = ctx.bus.send_goal(names.MOVE_TO, MoveToGoal(place=str(arg)))
        return True

    def _side_step(self, ctx: TaskContext, person: Point) -> bool:
        """Step across the line of sight to ``person`` (away from the map's light sources
        when it has any) and look at them again; False when no side is free."""
        pose = self._pose(ctx)
        if pose is None:
            return False
        bearing = math.atan2(person.y - pose.y, person.x - pose.x)
        sides = []
        for sign in (1.0, -1.0):
            x = pose.x - sign * SIDE_STEP_M * math.sin(bearing)
            y = pose.y + sign * SIDE_STEP_M * math.cos(bearing)
            if self.world.is_free(x, y, ROBOT_CLEARANCE_M):
                sides.append((self._glare(person, x, y), x, y))
        if not sides:
            return False
        _, x, y = min(sides)
        self._stop_motion()
        self.side_steps_left -= 1
        facing = math.atan2(person.y - y, person.x - x)
        self.steps.appendleft(("look", person))
        self.steps.appendleft(("step", Pose2D(x, y, facing)))
        self.step_until = ctx.now()
        ctx.event("search_side_step", person=self.person, x=round(x, 2), y=round(y, 2))
        return True

    def _glare(self, person: Point, x: float, y: float) -> float:
        """How closely a light source lines up behind the person seen from (x, y): the
        negative of the smallest angle between the viewing ray and a light's bearing."""
        ray = math.atan2(person.y - y, person.x - x)
        angles = [
            abs(math.remainder(math.atan2(light.y - person.y, light.x - person.x) - ray, math.tau))
            for light in self.world.home.lights
        ]
        return -min(angles, default=0.0)

    def update(self, ctx: TaskContext) -> TaskStatus:
        backlit: Point | None = None
        for seen in ctx.need(ctx.modules.perception, "perception").look():
            if seen.name == self.person:
                self.sightings.append(seen.position)
            elif seen.name is None and getattr(seen, "face_backlit", False):
                backlit = seen.position
        if (
            backlit is not None
            and len(self.sightings) < self.needed
            and self.side_steps_left > 0
            and not any(kind in ("step", "look") for kind, _ in self.steps)
            and not (self.goal is not None and self.goal.goal.pose is not None)
            and self._side_step(ctx, backlit)
        ):
            return TaskStatus.RUNNING
        if len(self.sightings) >= self.needed:
            self._stop_motion()
            mid = len(self.sightings) // 2
            xs, ys, zs = (
                sorted(axis)
                for axis in zip(*((p.x, p.y, p.z) for p in self.sightings), strict=True)
            )
            position = Point(xs[mid], ys[mid], zs[mid])
            room = self.world.room_at(position.x, position.y)
            ctx.blackboard["person_position"] = position
            ctx.blackboard["person_room"] = room
            self.detail.update(
                {"position": [round(position.x, 2), round(position.y, 2)], "room": room}
            )
            ctx.event("person_found", person=self.person, room=room)
            return TaskStatus.SUCCESS
        if self.goal is not None:
            if not self.goal.done:
                return TaskStatus.RUNNING
            was_goto = self.goal.goal.place is not None
            self.goal = None
            if was_goto:
                self._look_around(ctx, turn=False)
        elif ctx.now() < self.step_until:
            return TaskStatus.RUNNING
        if not self._start_step(ctx):
            self.detail["reason"] = "not_found"
            return TaskStatus.FAILURE
        return TaskStatus.RUNNING

    def _stop_motion(self) -> None:
        if self.goal is not None and not self.goal.done:
            self.goal.cancel()
        self.goal = None

    def cancel(self, ctx: TaskContext) -> None:
        self._stop_motion()
