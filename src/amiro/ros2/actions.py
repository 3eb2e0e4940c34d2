"""Actions across processes as real ROS 2 actions (rclpy's ``ActionServer``/``ActionClient``).

Goal, feedback, result and cancel travel as the action type's own messages with the
standard ``action_msgs/GoalStatus`` codes, so ``ros2 action send_goal``, RViz or any
client written against the type (a Nav2 client for ``/navigate_to_pose``) can drive amiro.

:class:`ActionExporter` serves the action for the local bus's server; :class:`RemoteActionServer`
registers on the caller's bus under the action's name, so ``bus.send_goal`` works unchanged
whichever process runs the server.  As for every bridge, rclpy's callbacks only queue what
arrived; the bus acts on it when it spins, never inside a ROS 2 callback.

rclpy polls a pending execute coroutine on every executor turn, which would turn each
``spin(timeout)`` into a busy loop while a goal runs; so the server executes nothing while
the bus goal runs: the accepted goal is marked executing, feedback is published from the
bus's side, and rclpy's execute step only runs, once, when the bus goal has ended.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from amiro.core.bus import ActionServer, BusError, GoalHandle, GoalStatus
from amiro.ros2.context import RosContext
from amiro.ros2.endpoint import WireEndpoint
from amiro.ros2.interfaces import ActionCodec, WireError

AnyHandle = GoalHandle[Any, Any, Any]
AnyCodec = ActionCodec[Any, Any, Any]
# action_msgs/msg/GoalStatus codes
STATUS_CODES = {
    GoalStatus.EXECUTING: 2,
    GoalStatus.SUCCEEDED: 4,
    GoalStatus.CANCELED: 5,
    GoalStatus.ABORTED: 6,
}
FROM_CODE = {code: status for status, code in STATUS_CODES.items()}


def _rclpy_action() -> Any:
    import rclpy.action

    return rclpy.action


@dataclass
class _Served:
    """A goal that arrived over ROS 2 and runs on the local bus."""

    handle: AnyHandle
    started: float
    ros_goal: Any = None  # rclpy's ServerGoalHandle, once accepted
    early: Any = None  # feedback given before rclpy accepted the goal: sent on acceptance


class ActionExporter(WireEndpoint):
    """Server side: goals arriving over ROS 2 run on this process's local action server."""

    def __init__(self, ros: RosContext, codec: AnyCodec) -> None:
        super().__init__(ros, codec.name, f"ros2_serve:{codec.ros_name}")
        self.codec = codec
        self.active: dict[bytes, _Served] = {}
        self._decided: dict[int, tuple[Any, _Served]] = {}  # id(goal msg) -> accepted goal
        self._server: Any = None

    def on_start(self) -> None:
        super().on_start()
        action = _rclpy_action()
        self._server = action.ActionServer(
            self.ros.node,
            self.codec.action,
            self.codec.ros_name,
            execute_callback=self._finish,
            goal_callback=self._on_goal_request,
            handle_accepted_callback=self._on_accepted,
            cancel_callback=self._on_cancel_request,
        )

    def on_stop(self) -> None:
        for served in list(self.active.values()):
            served.handle.cancel()
        if self._server is not None:
            self._server.destroy()
            self._server = None

    # --- rclpy's side: queue, answer later --------------------------------------------------
    async def _on_goal_request(self, msg: Any) -> Any:
        from rclpy.task import Future

        decision = Future(executor=self.ros.executor)  # type: ignore[no-untyped-call]
        self._queue("goal", (msg, decision))
        return await decision  # the bus's verdict, on its next turn

    def _on_accepted(self, ros_goal: Any) -> None:
        _msg, served = self._decided.pop(id(ros_goal.request))
        served.ros_goal = ros_goal
        self.active[bytes(ros_goal.goal_id.uuid)] = served
        from rclpy.impl.implementation_singleton import rclpy_implementation

        # executing from now on, without an execute coroutine (see the module's docstring)
        ros_goal._update_state(rclpy_implementation.GoalEvent.EXECUTE)
        if served.early is not None:
            self._feedback(served, served.early)
        served.handle.on_done(lambda _h: self._server.notify_execute(ros_goal, self._finish))

    def _on_cancel_request(self, ros_goal: Any) -> Any:
        served = self.active.get(bytes(ros_goal.goal_id.uuid))
        if served is None:
            return _rclpy_action().CancelResponse.REJECT
        self._queue("cancel", served)
        return _rclpy_action().CancelResponse.ACCEPT

    def _finish(self, ros_goal: Any) -> Any:
        """rclpy's execute step, run once the bus goal has ended: its final state and result."""
        served = self.active.pop(bytes(ros_goal.goal_id.uuid))
        status = served.handle.status
        if status is GoalStatus.SUCCEEDED:
            ros_goal.succeed()
        elif status is GoalStatus.CANCELED and ros_goal.is_cancel_requested:
            ros_goal.canceled()
        else:  # aborted, or canceled on the bus's side: no ROS 2 client asked for it
            ros_goal.abort()
        self.stats.sent += 1
        return self.codec.result_to_ros(served.handle.result, status)

    # --- the bus's side ---------------------------------------------------------------------
    def handle(self, kind: str, msg: Any) -> None:
        if kind == "cancel":
            msg.handle.cancel()
            return
        goal_msg, decision = msg
        decision.set_result(self._decide(goal_msg))

    def _decide(self, goal_msg: Any) -> Any:
        reject = _rclpy_action().GoalResponse.REJECT
        try:
            goal = self.codec.goal_from_ros(goal_msg)
        except WireError as exc:
            self.stats.errors += 1
            self.log.warning("goal for %s rejected: %s", self.codec.ros_name, exc)
            return reject
        try:
            handle = self.runtime.bus.send_goal(self.interface, goal)
        except BusError as exc:
            self.log.warning("goal for %s rejected: %s", self.codec.ros_name, exc)
            return reject
        if handle.status is GoalStatus.REJECTED:
            return reject
        served = _Served(handle, self.now(), early=handle.feedback)  # given in execute
        handle.on_feedback(lambda fb: self._feedback(served, fb))
        self._decided[id(goal_msg)] = (goal_msg, served)
        return _rclpy_action().GoalResponse.ACCEPT

    def _feedback(self, served: _Served, feedback: Any) -> None:
        if served.ros_goal is None:
            served.early = feedback  # the latest only, as a late ROS 2 subscriber would get
            return
        elapsed = self.now() - served.started
        served.ros_goal.publish_feedback(self.codec.feedback_to_ros(feedback, elapsed))
        self.stats.sent += 1


@dataclass
class _Pending:
    handle: AnyHandle
    since: float  # runtime time: sent, or the server last seen
    ros_goal: Any = None  # rclpy's ClientGoalHandle once accepted
    sent: bool = False
    cancel: bool = False
    waiting: list[str] = field(default_factory=list)


class RemoteActionServer(WireEndpoint, ActionServer[Any, Any, Any]):
    """Client side: stands on the local bus for an action server living in another process.

    A goal waits until the server is discovered; one whose server is not there (or goes away)
    for ``timeout_s`` aborts with the reason ``server_lost``.
    """

    def __init__(
        self,
        ros: RosContext,
        codec: AnyCodec,
        timeout_s: float = 3.0,
        check_period: float = 0.25,
    ) -> None:
        super().__init__(ros, codec.name, f"ros2_call:{codec.ros_name}")
        self.codec = codec
        self.timeout_s = timeout_s
        self.check_period = check_period
        self.pending: dict[int, _Pending] = {}
        self._count = 0
        self._client: Any = None

    def on_start(self) -> None:
        super().on_start()
        self._client = _rclpy_action().ActionClient(
            self.ros.node, self.codec.action, self.codec.ros_name
        )
        self.create_action_server(self.interface, self)
        self.create_timer(self.check_period, self._check)

    def on_stop(self) -> None:
        for key in list(self.pending):
            pending = self.pending[key]
            if pending.ros_goal is not None:
                pending.ros_goal.cancel_goal_async()
            self._fail(key, "bridge_stopped")
        if self._client is not None:
            self._client.destroy()
            self._client = None

    # --- the local bus's side -------------------------------------------------------------
    def execute(self, handle: AnyHandle) -> None:
        self._count += 1
        self.pending[self._count] = _Pending(handle, self.now())
        self._send(self._count)

    def cancel(self, handle: AnyHandle) -> None:
        for pending in self.pending.values():
            if pending.handle is handle:
                pending.cancel = True
                if pending.ros_goal is not None:
                    pending.ros_goal.cancel_goal_async()

    def _send(self, key: int) -> None:
        pending = self.pending[key]
        if pending.sent or not self._client.server_is_ready():
            return  # not discovered yet: the check timer tries again
        pending.sent, pending.since = True, self.now()
        future = self._client.send_goal_async(
            self.codec.goal_to_ros(pending.handle.goal),
            feedback_callback=lambda msg: self._queue("feedback", (key, msg)),
        )
        future.add_done_callback(lambda f: self._queue("accepted", (key, f)))
        self.stats.sent += 1

    # --- what rclpy queued ----------------------------------------------------------------
    def handle(self, kind: str, msg: Any) -> None:
        key, data = msg
        pending = self.pending.get(key)
        if pending is None:
            return  # a goal we gave up on
        if kind == "feedback":
            pending.handle.publish_feedback(self.codec.feedback_from_ros(data.feedback))
        elif kind == "accepted":
            self._on_accepted(key, pending, data.result())
        else:
            self._on_result(key, pending, data.result())

    def _on_accepted(self, key: int, pending: _Pending, ros_goal: Any) -> None:
        if not ros_goal.accepted:
            del self.pending[key]
            pending.handle.reject(self.codec.failure("rejected"))
            return
        pending.ros_goal = ros_goal
        if pending.cancel:
            ros_goal.cancel_goal_async()
        ros_goal.get_result_async().add_done_callback(lambda f: self._queue("result", (key, f)))

    def _on_result(self, key: int, pending: _Pending, response: Any) -> None:
        status = FROM_CODE.get(int(response.status))
        if status is None or not status.done:
            raise WireError(f"a result must carry a final status, not {response.status}")
        del self.pending[key]
        result = self.codec.result_from_ros(response.result, status)
        handle = pending.handle
        end = {
            GoalStatus.SUCCEEDED: handle.succeed,
            GoalStatus.ABORTED: handle.abort,
            GoalStatus.CANCELED: handle.canceled,
        }[status]
        end(result)

    def _check(self) -> None:
        now, ready = self.now(), self._client.server_is_ready()
        for key in list(self.pending):
            pending = self.pending[key]
            if ready:
                pending.since = now
                self._send(key)
            elif now - pending.since > self.timeout_s:
                lost = f"no answer from {self.codec.ros_name} for {self.timeout_s:g} s"
                self._fail(key, f"server_lost: {lost}")

    def _fail(self, key: int, reason: str) -> None:
        pending = self.pending.pop(key)
        self.log.warning("goal of %s aborted: %s", self.codec.ros_name, reason)
        pending.handle.abort(self.codec.failure(reason))
