"""A plain rclpy Nav2 client that knows nothing of amiro: NavigateToPose on /navigate_to_pose.

Usage: nav2_client.py X1 Y1 X2 Y2.  Sends a goal to (X1, Y1) and waits for its result, then
a goal to (X2, Y2) which it cancels once half of the way is done, then watches the
simulator's ground truth for a while.  Prints one JSON line: per goal the feedback count,
the first and last distance_remaining, the largest navigation_time and recoveries, the
final status and error code, and the true pose at the end; after the cancel, how far the
robot still moved.
"""

import json
import math
import sys
import time

import rclpy
from action_msgs.msg import GoalStatus
from geometry_msgs.msg import PoseStamped
from nav2_msgs.action import NavigateToPose
from rclpy.action import ActionClient

WAIT_S = 120.0  # generous: a loaded machine runs the simulator slowly


def spin_until(node, done, timeout_s):
    deadline = time.monotonic() + timeout_s
    while not done() and time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.05)
    return done()


def goal_to(x, y):
    goal = NavigateToPose.Goal()
    goal.pose.header.frame_id = "map"
    goal.pose.pose.position.x, goal.pose.pose.position.y = x, y
    goal.pose.pose.orientation.w = 1.0
    return goal


def half_way(feedback, fraction):
    """Whether the robot has done ``1 - fraction`` of the way (by distance_remaining)."""
    if len(feedback) < 2:
        return False
    first = feedback[0].feedback.distance_remaining
    return feedback[-1].feedback.distance_remaining < fraction * first


def describe(node, target, names):
    """``ros2 param describe`` and ``get`` on another node: {name: [description, value]}."""
    from rcl_interfaces.srv import DescribeParameters, GetParameters

    out = {}
    describing = node.create_client(DescribeParameters, f"{target}/describe_parameters")
    getting = node.create_client(GetParameters, f"{target}/get_parameters")
    if not (describing.wait_for_service(timeout_sec=WAIT_S) and getting.wait_for_service(5.0)):
        return out
    described = describing.call_async(DescribeParameters.Request(names=names))
    got = getting.call_async(GetParameters.Request(names=names))
    spin_until(node, lambda: described.done() and got.done(), WAIT_S)
    answers = zip(names, described.result().descriptors, got.result().values, strict=True)
    for name, d, v in answers:
        out[name] = [d.description, d.read_only, v.string_value]
    return out


def main() -> None:
    x1, y1, x2, y2 = map(float, sys.argv[1:5])
    rclpy.init()
    node = rclpy.create_node("plain_nav2_client")
    truth = {}

    def on_truth(msg: PoseStamped) -> None:
        truth["pose"] = (msg.pose.position.x, msg.pose.position.y)

    node.create_subscription(PoseStamped, "/amiro/sim/ground_truth", on_truth, 10)
    client = ActionClient(node, NavigateToPose, "navigate_to_pose")
    report = {"server": spin_until(node, client.server_is_ready, WAIT_S)}
    report["parameters"] = describe(node, "/amiro_sim", ["role", "navigation.backend"])
    for name, (x, y), cancel_at in (("first", (x1, y1), None), ("second", (x2, y2), 0.5)):
        feedback = []
        sent = client.send_goal_async(goal_to(x, y), feedback_callback=feedback.append)
        spin_until(node, sent.done, WAIT_S)
        handle = sent.result()
        entry = {"accepted": bool(handle.accepted)}
        result = handle.get_result_async()
        if cancel_at is not None:
            spin_until(node, lambda fb=feedback, at=cancel_at: half_way(fb, at), WAIT_S)
            entry["canceled_at_m"] = feedback[-1].feedback.distance_remaining
            canceling = handle.cancel_goal_async()
            spin_until(node, canceling.done, WAIT_S)
            entry["cancel_accepted"] = len(canceling.result().goals_canceling) == 1
        spin_until(node, result.done, WAIT_S)
        answer = result.result()
        fb = [m.feedback for m in feedback]
        entry.update(
            status=answer.status,
            succeeded=answer.status == GoalStatus.STATUS_SUCCEEDED,
            canceled=answer.status == GoalStatus.STATUS_CANCELED,
            error_code=answer.result.error_code,
            feedback=len(fb),
            first_remaining_m=fb[0].distance_remaining if fb else None,
            last_remaining_m=fb[-1].distance_remaining if fb else None,
            navigation_time_s=max(
                (f.navigation_time.sec + f.navigation_time.nanosec * 1e-9) for f in fb
            )
            if fb
            else None,
            recoveries=max((f.number_of_recoveries for f in fb), default=None),
            frame=fb[-1].current_pose.header.frame_id if fb else None,
        )
        spin_until(node, lambda: False, 0.5)  # a fresh ground truth
        entry["true_pose"] = truth.get("pose")
        entry["to_goal_m"] = math.dist(truth["pose"], (x, y)) if "pose" in truth else None
        report[name] = entry
    stopped_at = truth.get("pose")
    spin_until(node, lambda: False, 3.0)  # does the robot keep going after the cancel?
    report["moved_after_cancel_m"] = (
        math.dist(stopped_at, truth["pose"]) if stopped_at is not None else None
    )
    print(json.dumps(report))
    client.destroy()
    node.destroy_node()
    rclpy.shutdown()


if __name__ == "__main__":
    main()
