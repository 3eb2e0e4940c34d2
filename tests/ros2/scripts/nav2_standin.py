"""A stand-in Nav2 in plain rclpy: serves /navigate_to_pose (nav2_msgs/action/NavigateToPose).

Also serves Nav2's behaviour server's /backup and /drive_on_heading (nav2_msgs BackUp,
DriveOnHeading), not /spin.

Usage: nav2_standin.py relay|abort.
  relay: the robot's own navigation does the driving: each NavigateToPose goal becomes a
         pose goal of the robot's MoveTo action (the simulated robot process serves it as
         amiro_interfaces/action/MoveTo), each BackUp / DriveOnHeading goal a goal of its
         forward primitive (amiro_interfaces/action/Forward); feedback is passed on as
         Nav2's, and a cancel is passed on too.  Counts the goals in a JSON line at exit.
  abort: every goal is accepted, then ABORTED: NavigateToPose with ComputePathToPose's
         NO_VALID_PATH, BackUp / DriveOnHeading with COLLISION_AHEAD.
"""

import json
import signal
import sys

import rclpy
from action_msgs.msg import GoalStatus
from amiro_interfaces.action import Forward, MoveTo
from nav2_msgs.action import BackUp, DriveOnHeading, NavigateToPose
from rclpy.action import ActionClient, ActionServer, CancelResponse
from rclpy.signals import SignalHandlerOptions
from rclpy.task import Future

NO_VALID_PATH = 208
COLLISION_AHEAD = {"backup": 714, "drive_on_heading": 723}
UNKNOWN = {"backup": 710, "drive_on_heading": 720}


def yaw(q):
    import math

    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def main() -> None:
    mode = sys.argv[1]
    stop = []
    signal.signal(signal.SIGTERM, lambda *_: stop.append(True))
    rclpy.init(signal_handler_options=SignalHandlerOptions.NO)
    node = rclpy.create_node("nav2_standin")
    robot = ActionClient(node, MoveTo, "/amiro/navigation/move_to")
    forward = ActionClient(node, Forward, "/amiro/navigation/forward")
    counts = {"goals": 0, "succeeded": 0, "aborted": 0, "canceled": 0}
    behaviors = {"backup": 0, "drive_on_heading": 0, "succeeded": 0}

    async def wait(future):
        while not future.done():
            await sleep_a_little()
        return future.result()

    async def sleep_a_little():
        done = Future()
        timer = node.create_timer(0.02, lambda: done.done() or done.set_result(True))
        await done
        timer.cancel()
        node.destroy_timer(timer)

    async def execute(goal_handle):
        counts["goals"] += 1
        result = NavigateToPose.Result()
        if mode == "abort":
            result.error_code, result.error_msg = NO_VALID_PATH, "no valid path"
            goal_handle.abort()
            counts["aborted"] += 1
            return result
        target = goal_handle.request.pose.pose
        goal = MoveTo.Goal(to_pose=True)
        goal.pose.x, goal.pose.y = target.position.x, target.position.y
        goal.pose.theta = yaw(target.orientation)

        def relay(msg):
            fb = NavigateToPose.Feedback(
                distance_remaining=msg.feedback.remaining_m,
                number_of_recoveries=msg.feedback.recoveries,
            )
            fb.current_pose.header.frame_id = "map"
            fb.current_pose.pose.position.x = msg.feedback.pose.x
            fb.current_pose.pose.position.y = msg.feedback.pose.y
            goal_handle.publish_feedback(fb)

        response = await relay_to(robot, goal, goal_handle, relay)
        if response is None:
            result.error_code, result.error_msg = NO_VALID_PATH, "robot refused the goal"
            goal_handle.abort()
            counts["aborted"] += 1
            return result
        if goal_handle.is_cancel_requested:
            goal_handle.canceled()
            counts["canceled"] += 1
        elif response.status == GoalStatus.STATUS_SUCCEEDED:
            goal_handle.succeed()
            counts["succeeded"] += 1
        else:
            reason = response.result.reason
            result.error_code = NO_VALID_PATH if reason == "unreachable" else 105
            result.error_msg = reason
            goal_handle.abort()
            counts["aborted"] += 1
        return result

    async def relay_to(client, goal, goal_handle, relay):
        """The goal's response and its result's, the caller's cancel passed on."""
        while not client.server_is_ready():
            await sleep_a_little()
        sent = await wait(client.send_goal_async(goal, feedback_callback=relay))
        if not sent.accepted:
            return None
        answer = sent.get_result_async()
        while not answer.done():
            if goal_handle.is_cancel_requested:
                await wait(sent.cancel_goal_async())
                break
            await sleep_a_little()
        return await wait(answer)

    def behavior(kind, action_type):
        async def execute_behavior(goal_handle):
            behaviors[kind] += 1
            result = action_type.Result()
            if mode == "abort":
                result.error_code, result.error_msg = COLLISION_AHEAD[kind], "collision ahead"
                goal_handle.abort()
                return result
            distance = abs(goal_handle.request.target.x)
            sign = -1.0 if kind == "backup" else 1.0
            goal = Forward.Goal(distance=sign * distance, speed=abs(goal_handle.request.speed))

            def relay(msg):
                travelled = max(0.0, distance - msg.feedback.remaining)
                goal_handle.publish_feedback(action_type.Feedback(distance_traveled=travelled))

            response = await relay_to(forward, goal, goal_handle, relay)
            if goal_handle.is_cancel_requested:
                goal_handle.canceled()
            elif response is not None and response.status == GoalStatus.STATUS_SUCCEEDED:
                behaviors["succeeded"] += 1
                goal_handle.succeed()
            else:
                reason = response.result.reason if response is not None else "refused"
                blocked = reason == "blocked"
                result.error_code = COLLISION_AHEAD[kind] if blocked else UNKNOWN[kind]
                result.error_msg = reason
                goal_handle.abort()
            return result

        return execute_behavior

    for kind, action_type in (("backup", BackUp), ("drive_on_heading", DriveOnHeading)):
        ActionServer(
            node,
            action_type,
            kind,
            execute_callback=behavior(kind, action_type),
            cancel_callback=lambda _goal: CancelResponse.ACCEPT,
        )
    ActionServer(
        node,
        NavigateToPose,
        "navigate_to_pose",
        execute_callback=execute,
        cancel_callback=lambda _goal: CancelResponse.ACCEPT,
    )
    while not stop:
        rclpy.spin_once(node, timeout_sec=0.1)
    print(json.dumps({**counts, "behaviors": behaviors}), flush=True)
    node.destroy_node()
    rclpy.shutdown()


if __name__ == "__main__":
    main()
