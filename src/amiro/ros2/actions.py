"""Actions across processes as real ROS 2 actions (rclpy's ``ActionServer``/``ActionClient``).

Goal, feedback, result and cancel travel as the action type's own messages with the
standard ``action_msgs/GoalStatus`` codes, so ``ros2 action send_goal``, RViz or any
client written against the type (a Nav2 client for ``/navigate_to_pose``) can drive amiro.

:class:`ActionExporter` serves the action for the local bus's server; :class:`RemoteActionServer`
registers on the caller's bus under the action's name, so ``bus.send_goal`` works unchanged
whichever process runs the server.  As for every bridge, rclpy's callbacks only queue what
arrived; the bus acts on it when it spins, never inside a ROS 2 callback.

rclpy runs a pending coroutine first on every executor turn (and takes nothing else in
that turn), so nothing here awaits: the server marks an accepted goal executing itself,
feedback is published from the bus's side, and rclpy's execute step only runs, once, when
the bus goal has ended.
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
# An exporter's status writer offers this liveliness lease; a caller watching it hears of a
# SIGKILLed server within it, where DDS drops the participant only when its own lease ends.
LIVELINESS_S = 2.0


def status_qos() -> Any:
    """The action status topic's default QoS with an automatic liveliness lease: compatible
    with every client (they request an infinite lease), watched by :class:`RemoteActionServer`."""
    from rclpy.duration import Duration
    from rclpy.qos import LivelinessPolicy, QoSProfile, qos_profile_action_status_default

    return QoSProfile(  # type: ignore[no-untyped-call]
        history=qos_profile_action_status_default.history,
        depth=qos_profile_action_status_default.depth,
        reliability=qos_profile_action_status_default.reliability,
        durability=qos_profile_action_status_default.durability,
        liveliness=LivelinessPolicy.AUTOMATIC,
        liveliness_lease_duration=Duration(seconds=LIVELINESS_S),
    )


def _rclpy_action() -> Any:
    import rclpy.action

    return rclpy.action


@dataclass
class _Served:
    """A goal that arrived over ROS 2 and runs on the local bus."""

    goal: Any
    started: float
    ros_goal: Any  # rclpy's ServerGoalHandle
    handle: AnyHandle | None = None  # once the bus has it
    refused: str = ""  # why the bus refused it after all


class ActionExporter(WireEndpoint):
    """Server side: goals arriving over ROS 2 run on this process's local action server.

    A goal request is answered inside rclpy's callback by the bus server's ``accept`` (a
    check, nothing runs); the goal itself starts on the bus's next turn.  Nothing here
    awaits: a pending rclpy coroutine is run first by every executor turn, so waiting
    for the bus there would keep ROS 2's own messages (a followed ``/clock``) from ever
    being taken, and the process would stall.
    """

    def __init__(self, ros: RosContext, codec: AnyCodec) -> None:
        super().__init__(ros, codec.name, f"ros2_serve:{codec.ros_name}")
        self.codec = codec
        self.active: dict[bytes, _Served] = {}
        self._decoded: dict[int, tuple[Any, Any]] = {}  # id(goal msg) -> (msg, goal)
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
            status_pub_qos_profile=status_qos(),
        )

    def on_stop(self) -> None:
        for served in list(self.active.values()):
            if served.handle is not None:
                served.handle.cancel()
        if self._server is not None:
            self._server.destroy()
            self._server = None

    # --- rclpy's side ---------------------------------------------------------------------
    def _on_goal_request(self, msg: Any) -> Any:
        response = _rclpy_action().GoalResponse
        try:
            goal = self.codec.goal_from_ros(msg)
        except WireError as exc:
            self.stats.errors += 1
            self.log.warning("goal for %s rejected: %s", self.codec.ros_name, exc)
            return response.REJECT
        if not (self.running and self.runtime.bus.accepts(self.interface, goal)):
            return response.REJECT
        self._decoded[id(msg)] = (msg, goal)
        return response.ACCEPT

    def _on_accepted(self, ros_goal: Any) -> None:
        _msg, goal = self._decoded.pop(id(ros_goal.request))
        from rclpy.impl.implementation_singleton import rclpy_implementation

        # Executing from now on, without an execute coroutine.  rclpy has no public way:
        # ServerGoalHandle.execute() also schedules the execute callback at once, and one
        # that waits for the bus goal is re-run by every executor turn, taking nothing else
        # (see the module's docstring and test_a_goal_request_never_starves_...).
        ros_goal._update_state(rclpy_implementation.GoalEvent.EXECUTE)
        served = _Served(goal, self.now(), ros_goal)
        self.active[bytes(ros_goal.goal_id.uuid)] = served
        self._queue("start", served)

    def _on_cancel_request(self, ros_goal: Any) -> Any:
        served = self.active.get(bytes(ros_goal.goal_id.uuid))
        if served is None:
            return _rclpy_action().CancelResponse.REJECT
        self._queue("cancel", served)  # after its "start": the inbox keeps the order
        return _rclpy_action().CancelResponse.ACCEPT

    def _finish(self, ros_goal: Any) -> Any:
        """rclpy's execute step, run once the bus goal has ended: its final state and result."""
        served = self.active.pop(bytes(ros_goal.goal_id.uuid))
        self.stats.sent += 1
        handle = served.handle
        if handle is None:  # the bus refused it when it came to start it
            ros_goal.abort()
            return self.codec.result_to_ros(self.codec.failure(served.refused), GoalStatus.ABORTED)
        status = handle.status
        if status is GoalStatus.SUCCEEDED:
            ros_goal.succeed()
        elif status is GoalStatus.CANCELED and ros_goal.is_cancel_requested:
            ros_goal.canceled()
        else:  # aborted, or canceled on the bus's side: no ROS 2 client asked for it
            ros_goal.abort()
        return self.codec.result_to_ros(handle.result, status)

    # --- the bus's side ---------------------------------------------------------------------
    def handle(self, kind: str, msg: Any) -> None:
        served: _Served = msg
        if kind == "cancel":
            if served.handle is not None:
                served.handle.cancel()
            return
        try:
            handle = self.runtime.bus.send_goal(self.interface, served.goal)
        except BusError as exc:
            self._refused(served, str(exc))
            return
        if handle.status is GoalStatus.REJECTED:
            self._refused(served, "rejected")
            return
        served.handle = handle
        if handle.feedback is not None:  # given as it started, before we could listen
            self._feedback(served, handle.feedback)
        handle.on_feedback(lambda fb: self._feedback(served, fb))
        handle.on_done(lambda _h: self._server.notify_execute(served.ros_goal, self._finish))

    def _refused(self, served: _Served, reason: str) -> None:
        self.log.warning("goal for %s refused: %s", self.codec.ros_name, reason)
        served.refused = reason
        self._server.notify_execute(served.ros_goal, self._finish)

    def _feedback(self, served: _Served, feedback: Any) -> None:
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
        self.server_heard: float | None = None  # runtime time the server was last seen
        self.lost = False  # the server's status writer lost its liveliness (killed)
        self._count = 0
        self._client: Any = None
        self._watch: Any = None

    def on_start(self) -> None:
        super().on_start()
        self._client = _rclpy_action().ActionClient(
            self.ros.node, self.codec.action, self.codec.ros_name
        )
        self._watch_liveliness()
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
        if self._watch is not None:
            self.ros.node.destroy_subscription(self._watch)
            self._watch = None

    def _watch_liveliness(self) -> None:
        """A second reader of the status topic, only for its liveliness events (a server
        that is not amiro's offers no lease: the QoS do not match and nothing is heard)."""
        from rclpy.event_handler import SubscriptionEventCallbacks

        self._watch = self.ros.node.create_subscription(
            self.ros.types.message_class("action_msgs/msg/GoalStatusArray"),
            f"{self.codec.ros_name}/_action/status",
            lambda _msg: None,
            status_qos(),
            event_callbacks=SubscriptionEventCallbacks(
                liveliness=lambda info: self._queue("liveliness", (0, info))
            ),
        )

    @property
    def available(self) -> bool:
        """Whether the ROS 2 server is on the graph now (a caller may route elsewhere)."""
        return self._client is not None and not self.lost and bool(self._client.server_is_ready())

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
        if pending.sent or not self.available:
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
        if kind == "liveliness":
            self._on_liveliness(data)
            return
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

    def _on_liveliness(self, info: Any) -> None:
        if info.alive_count > 0:
            self.lost = False
        elif info.not_alive_count_change > 0:  # lost, not a writer deleted cleanly
            self.lost = True
            lost = f"{self.codec.ros_name} stopped asserting liveliness ({LIVELINESS_S:g} s lease)"
            for key in [k for k, p in self.pending.items() if p.sent]:
                self._fail(key, f"server_lost: {lost}")

    def _check(self) -> None:
        now, ready = self.now(), self.available
        if ready:
            self.server_heard = now
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
