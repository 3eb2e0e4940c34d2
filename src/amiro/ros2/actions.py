"""Actions across processes, the way actionlib did it before ROS 2 actions: plain topics.

``<action>/goal``, ``/cancel``, ``/feedback`` and ``/result`` carry JSON in std_msgs/String
with a goal id (a UUID); ``<action>/status`` is a standard action_msgs/GoalStatusArray that
the server publishes periodically, listing its goals.  That status is also the server's
heartbeat: a client whose goal is missing from it re-sends the goal (a goal sent before
discovery finished is not lost), and a goal not listed for ``timeout_s`` aborts with the
reason ``server_lost``.  :class:`RemoteActionServer` registers on the caller's bus under the
action's name, so ``bus.send_goal`` works unchanged whichever process runs the server.
"""

from __future__ import annotations

import os
import uuid
from collections import OrderedDict
from dataclasses import dataclass
from typing import Any

from amiro.core.bus import ActionServer, BusError, GoalHandle, GoalStatus
from amiro.ros2.context import RosContext
from amiro.ros2.convert import ros_time
from amiro.ros2.endpoint import WireEndpoint
from amiro.ros2.interfaces import ActionSpec, WireError, envelope

STATUS_TYPE = "action_msgs/msg/GoalStatusArray"
# action_msgs/GoalStatus codes; a rejected goal never gets one (as in ROS 2, where
# rejection is the answer to the goal request): it only travels on the result topic.
STATUS_CODES = {
    GoalStatus.EXECUTING: 2,
    GoalStatus.SUCCEEDED: 4,
    GoalStatus.CANCELED: 5,
    GoalStatus.ABORTED: 6,
}
CANCELING = 3
FINAL_CODES = frozenset({4, 5, 6})

AnyHandle = GoalHandle[Any, Any, Any]


def goal_uuid(text: Any) -> str:
    try:
        return str(uuid.UUID(str(text)))
    except ValueError:
        raise WireError(f"goal_id {text!r} is not a UUID") from None


class ActionExporter(WireEndpoint):
    """Server side: goals arriving over ROS 2 run on this process's local action server."""

    def __init__(
        self, ros: RosContext, spec: ActionSpec, status_period: float = 0.5, keep: int = 100
    ) -> None:
        super().__init__(ros, spec.name, f"ros2_serve:{spec.name}")
        self.spec = spec
        self.status_period = status_period
        self.keep = keep  # finished goals remembered, to answer a re-sent goal again
        self.active: dict[str, AnyHandle] = {}
        self.finished: OrderedDict[str, dict[str, Any]] = OrderedDict()
        self.incoming("goal")
        self.incoming("cancel")
        self.outgoing("feedback", depth=10)
        self.outgoing("result")
        self.outgoing("status", STATUS_TYPE, depth=10)

    def on_start(self) -> None:
        super().on_start()
        self.create_timer(self.status_period, self.publish_status)
        self.publish_status()

    def on_stop(self) -> None:
        for handle in list(self.active.values()):
            handle.cancel()

    def handle(self, kind: str, msg: Any) -> None:
        if kind == "goal":
            data = envelope(str(msg.data), "goal_id", "goal")
            self._on_goal(goal_uuid(data["goal_id"]), data["goal"])
        else:
            handle = self.active.get(goal_uuid(envelope(str(msg.data), "goal_id")["goal_id"]))
            if handle is not None:
                handle.cancel()

    def _on_goal(self, goal_id: str, payload: Any) -> None:
        if goal_id in self.active:
            return  # a re-send that crossed our status
        if goal_id in self.finished:
            self.send("result", self.finished[goal_id])
            return
        goal = self.spec.goal.load(payload)
        try:
            handle = self.runtime.bus.send_goal(self.interface, goal)
        except BusError as exc:
            self._finished(goal_id, GoalStatus.REJECTED, None, str(exc))
            return
        if handle.status is GoalStatus.REJECTED:
            self._finished(goal_id, GoalStatus.REJECTED, None, "rejected")
            return
        self.active[goal_id] = handle
        handle.on_feedback(lambda fb: self._feedback(goal_id, fb))
        handle.on_done(lambda h: self._done(goal_id, h))
        self.publish_status()

    def _feedback(self, goal_id: str, feedback: Any) -> None:
        self.send("feedback", {"goal_id": goal_id, "feedback": self.spec.feedback.dump(feedback)})

    def _done(self, goal_id: str, handle: AnyHandle) -> None:
        self.active.pop(goal_id, None)
        self._finished(goal_id, handle.status, handle.result, handle.status.value)

    def _finished(self, goal_id: str, status: GoalStatus, result: Any, reason: str) -> None:
        answer = {
            "goal_id": goal_id,
            "status": status.value,
            "result": None if result is None else self.spec.result.dump(result),
            "reason": reason,
        }
        self.finished[goal_id] = answer
        while len(self.finished) > self.keep:
            self.finished.popitem(last=False)
        self.send("result", answer)

    def publish_status(self) -> None:
        """The goals this server knows, as action_msgs/GoalStatusArray (also its heartbeat)."""
        types, stamp = self.ros.types, ros_time(self.ros.types, self.now())
        codes = {
            gid: CANCELING if h.cancel_requested else STATUS_CODES[h.status]
            for gid, h in self.active.items()
        }
        for gid, answer in self.finished.items():
            code = STATUS_CODES.get(GoalStatus(answer["status"]))
            if code is not None:
                codes[gid] = code
        statuses = [
            types.make(
                "action_msgs/msg/GoalStatus",
                goal_info=types.make(
                    "action_msgs/msg/GoalInfo",
                    goal_id=types.make(
                        "unique_identifier_msgs/msg/UUID", uuid=list(uuid.UUID(gid).bytes)
                    ),
                    stamp=stamp,
                ),
                status=code,
            )
            for gid, code in codes.items()
        ]
        self.send_ros("status", types.make(STATUS_TYPE, status_list=statuses))


@dataclass
class _Pending:
    handle: AnyHandle
    goal: dict[str, Any]
    last_heard: float
    acknowledged: bool = False


class RemoteActionServer(WireEndpoint, ActionServer[Any, Any, Any]):
    """Client side: stands on the local bus for an action server living in another process."""

    def __init__(
        self, ros: RosContext, spec: ActionSpec, timeout_s: float = 3.0, check_period: float = 0.25
    ) -> None:
        super().__init__(ros, spec.name, f"ros2_call:{spec.name}")
        self.spec = spec
        self.timeout_s = timeout_s
        self.check_period = check_period
        self.pending: dict[str, _Pending] = {}
        self.server_heard: float | None = None  # runtime time of the last status
        self._owner = f"{ros.node.get_fully_qualified_name()}/{os.getpid()}"
        self._count = 0
        self.outgoing("goal")
        self.outgoing("cancel")
        self.incoming("feedback", depth=10)
        self.incoming("result")
        self.incoming("status", STATUS_TYPE, depth=10)

    def on_start(self) -> None:
        super().on_start()
        self.create_action_server(self.interface, self)
        self.create_timer(self.check_period, self._check)

    def on_stop(self) -> None:
        for goal_id in list(self.pending):
            self.send("cancel", {"goal_id": goal_id})
            self._fail(goal_id, "bridge_stopped")

    # --- the local bus's side -------------------------------------------------------------
    def execute(self, handle: AnyHandle) -> None:
        self._count += 1
        goal_id = str(uuid.uuid5(uuid.NAMESPACE_URL, f"amiro:{self._owner}:{self._count}"))
        data = {"goal_id": goal_id, "goal": self.spec.goal.dump(handle.goal)}
        self.pending[goal_id] = _Pending(handle, data, self.now())
        self.send("goal", data)

    def cancel(self, handle: AnyHandle) -> None:
        for goal_id, pending in self.pending.items():
            if pending.handle is handle:
                self.send("cancel", {"goal_id": goal_id})

    # --- the wire's side ------------------------------------------------------------------
    def handle(self, kind: str, msg: Any) -> None:
        if kind == "status":
            self._on_status(msg)
            return
        data = envelope(str(msg.data), "goal_id")
        pending = self.pending.get(goal_uuid(data["goal_id"]))
        if pending is None:
            return  # another client's goal, or one we gave up on
        pending.last_heard = self.now()
        if kind == "feedback":
            pending.handle.publish_feedback(self.spec.feedback.load(data.get("feedback")))
        else:
            self._on_result(goal_uuid(data["goal_id"]), pending, data)

    def _on_result(self, goal_id: str, pending: _Pending, data: dict[str, Any]) -> None:
        try:
            status = GoalStatus(data.get("status"))
        except ValueError:
            raise WireError(f"unknown goal status {data.get('status')!r}") from None
        if not status.done:
            raise WireError("a result must carry a final status")
        raw = data.get("result")
        result = (
            self.spec.failure(str(data.get("reason", status.value)))
            if raw is None
            else self.spec.result.load(raw)
        )
        del self.pending[goal_id]
        handle = pending.handle
        end = {
            GoalStatus.SUCCEEDED: handle.succeed,
            GoalStatus.ABORTED: handle.abort,
            GoalStatus.CANCELED: handle.canceled,
            GoalStatus.REJECTED: handle.reject,
        }[status]
        end(result)

    def _on_status(self, msg: Any) -> None:
        now = self.now()
        self.server_heard = now
        listed = {
            str(uuid.UUID(bytes=bytes(s.goal_info.goal_id.uuid))): int(s.status)
            for s in msg.status_list
        }
        for goal_id, pending in self.pending.items():
            code = listed.get(goal_id)
            if code is not None:
                pending.acknowledged = True
                pending.last_heard = now
            if code in FINAL_CODES or (code is None and not pending.acknowledged):
                # never heard (sent before discovery) or its result got lost: the server
                # starts it, or answers a finished goal with its result again
                self.send("goal", pending.goal)

    def _check(self) -> None:
        now = self.now()
        for goal_id, pending in list(self.pending.items()):
            if now - pending.last_heard > self.timeout_s:
                self._fail(
                    goal_id,
                    f"server_lost: no answer from {self.interface} for {self.timeout_s:g} s",
                )

    def _fail(self, goal_id: str, reason: str) -> None:
        pending = self.pending.pop(goal_id)
        self.log.warning("goal %s of %s aborted: %s", goal_id, self.interface, reason)
        pending.handle.abort(self.spec.failure(reason))
