"""Plans, dispatches, monitors and re-plans until the goals hold or no plan exists.

The executive submits each plan as a behaviour to the engine's priority queue.  It follows
the engine's events: a failed task teaches the knowledge base why (the door is closed, the
person declined, the person is not in that room) and a fact that changes under the plan (the
lidar sees a door on the route closed) cancels the behaviour; either way it plans again from
where the robot now is, which ROSPlan leaves to its users.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from amiro.behavior.engine import BehaviorEngine, GraphRun
from amiro.behavior.planning.dispatch import plan_graph, step_index
from amiro.behavior.planning.explain import describe_plan, describe_step
from amiro.behavior.planning.knowledge import DoorState, KnowledgeBase
from amiro.behavior.planning.planner import HomePlanner, PlanOutcome, PlanStep
from amiro.behavior.planning.problem import Goal, RobotState
from amiro.core import names
from amiro.core.messages import BehaviorEvent, Pose2D
from amiro.core.node import Node

TICK_S = 0.1
ACTIVE = ("planning", "executing")


class PlanExecutive(Node):
    """``request`` goals; ``status`` ends as completed, no_plan or gave_up."""

    def __init__(
        self,
        planner: HomePlanner,
        kb: KnowledgeBase,
        engine: BehaviorEngine,
        pose: Callable[[], Pose2D | None],
        room_at: Callable[[float, float], str | None],
        name: str = "planner",
    ) -> None:
        super().__init__(name)
        self.planner = planner
        self.kb = kb
        self.engine = engine
        self.pose = pose
        self.room_at = room_at
        self.status = "idle"
        self.explanation = ""
        self.plans: list[PlanOutcome] = []
        self.runs: list[GraphRun] = []
        self.goals: list[Goal] = []
        self.blackboard: dict[str, Any] = {}
        self.behavior = "plan"
        self.priority = 5
        self._steps: list[PlanStep] = []
        self._next = 0
        self._replan_reason: str | None = None
        self._seen_version = -1
        self._start_room = ""

    def on_start(self) -> None:
        self.create_subscription(names.EVENTS, BehaviorEvent, self._on_event, depth=10_000)
        self.create_timer(TICK_S, self._tick)

    # --- requests -------------------------------------------------------------------------
    def request(
        self,
        goals: list[Goal],
        blackboard: dict[str, Any] | None = None,
        behavior: str = "plan",
        priority: int = 5,
    ) -> None:
        self.goals = list(goals)
        self.blackboard = dict(blackboard or {})
        self.behavior, self.priority = behavior, priority
        self.status = "planning"
        self._replan_reason = None

    @property
    def done(self) -> bool:
        return self.status not in ("idle", *ACTIVE)

    # --- the loop -------------------------------------------------------------------------
    def _tick(self) -> None:
        if self.status == "planning":
            self._plan()
        elif self.status == "executing" and self.kb.version != self._seen_version:
            self._seen_version = self.kb.version
            broken = self._plan_broken()
            if broken is not None:
                self._cancel_run()
                self._replan(broken)

    def _robot(self) -> RobotState | None:
        pose = self.pose()
        if pose is None:
            return None
        room = self.room_at(pose.x, pose.y)
        if room is None:  # on a threshold: the room of the nearest waypoint
            wps = self.kb.topology.waypoints.values()
            room = min(wps, key=lambda w: pose.distance_to(Pose2D(w.x, w.y))).room
        return RobotState(room, pose.x, pose.y)

    def _plan(self) -> None:
        robot = self._robot()
        if robot is None:
            return
        outcome = self.planner.plan(self.kb, robot, self.goals)
        self.plans.append(outcome)
        if not outcome.solved:
            self.status, self.explanation = "no_plan", outcome.explanation
            self._event("plan_failed", explanation=outcome.explanation, engine=outcome.engine)
            return
        self._steps, self._next = outcome.steps, 0
        self._start_room = robot.room
        self._seen_version = self.kb.version
        graph = plan_graph(
            outcome.steps, self.kb.topology, robot, self.behavior, self.priority, self.blackboard
        )
        self.runs.append(self.engine.submit(graph))
        self.status = "executing"
        self._event(
            "plan",
            number=len(self.plans),
            engine=outcome.engine,
            planning_ms=round(outcome.planning_ms, 1),
            steps=[str(s) for s in outcome.steps],
            summary=describe_plan(outcome.steps),
        )

    def _replan(self, reason: str) -> None:
        replans = len(self.plans) - 1
        if replans >= self.planner.config.max_replans:
            self.status = "gave_up"
            self.explanation = f"still failing after {replans} re-plans: {reason}"
            self._event("plan_failed", explanation=self.explanation)
            return
        self._event("replan", reason=reason, knowledge=self.kb.snapshot())
        self.status = "planning"

    def _cancel_run(self) -> None:
        if self.runs and not self.runs[-1].done:
            self.engine.cancel_graph(self.runs[-1].id)

    # --- monitoring -----------------------------------------------------------------------
    def _on_event(self, ev: BehaviorEvent) -> None:
        if self.status != "executing" or not self.runs or ev.graph != self.runs[-1].id:
            return
        if ev.type == "task_finished" and ev.task is not None:
            index = step_index(ev.task)
            if index is None or index >= len(self._steps):
                return
            if ev.detail.get("result") == "success":
                self._next = index + 1
            elif ev.detail.get("result") == "failure":
                detail = ev.detail.get("detail") or {}
                step = self._steps[index]
                self._learn(step, detail)
                reason = detail.get("reason") or detail.get("intent") or "failed"
                self._replan(f"{describe_step(step)} failed: {reason}")
        elif ev.type == "graph_finished" and ev.detail.get("outcome") == "completed":
            self.status = "completed"
            self._event("plan_completed", plans=len(self.plans))

    def _learn(self, step: PlanStep, detail: dict[str, Any]) -> None:
        """What a failed action says about the home."""
        now, a, kb = self.now(), step.args, self.kb
        if step.action == "cross" and kb.doors[a[0]] is DoorState.OPEN:
            kb.set_door(a[0], DoorState.CLOSED, now, "crossing failed")
        elif step.action in ("ask_open_door", "ask_clear"):
            if detail.get("reason") == "door_still_closed":
                kb.set_door(a[1], DoorState.LOCKED, now, f"{a[0]} could not open it")
            else:
                kb.declined(a[0], now)
        elif step.action == "move":
            kb.set_blocked(a[1], True, now, "move failed")
        elif step.action in ("approach", "search"):
            kb.person_not_found(a[0], self._room_of(a[1]), now)

    def _room_of(self, waypoint: str) -> str:
        wp = self.kb.topology.waypoints.get(waypoint)
        return wp.room if wp is not None else self._start_room  # START is not in the topology

    def _plan_broken(self) -> str | None:
        """The first remaining action the knowledge base now says cannot work."""
        kb = self.kb
        asked: set[str] = set()
        for step in self._steps[self._next :]:
            a = step.action
            if a == "ask_open_door":
                asked.add(step.args[1])
                if not kb.person(step.args[0]).willing:
                    return f"{step.args[0].title()} will not help"
            elif a == "cross" and step.args[0] not in asked:
                state = kb.doors[step.args[0]]
                if state is not DoorState.OPEN:
                    return f"door {step.args[0]} is {state} (seen on the way)"
            elif a == "move" and step.args[1] in kb.blocked:
                return f"the way to {step.args[1]} is blocked"
            elif a == "approach":
                room = kb.person(step.args[0]).room
                if room != self._room_of(step.args[1]):
                    return f"{step.args[0]} is now in {room or 'an unknown room'}"
        return None

    def _event(self, type_: str, **detail: Any) -> None:
        self.runtime.bus.publish(names.EVENTS, BehaviorEvent(self.now(), type_, None, None, detail))
