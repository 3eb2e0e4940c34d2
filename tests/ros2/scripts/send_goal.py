"""What ``ros2 action send_goal --feedback ACTION TYPE GOAL`` does, in plain rclpy.

Usage: send_goal.py ACTION TYPE GOAL_JSON, e.g.
  send_goal.py /amiro/behavior/recognize_activity amiro_interfaces/action/RecognizeActivity \
      '{"person": "anna", "activity": "drink_water"}'
Prints one JSON line: accepted, every feedback's fields, the final status code and the
result's fields.
"""

import importlib
import json
import sys
import time

import rclpy
from rclpy.action import ActionClient

WAIT_S = 120.0


def fields(msg):
    out = {}
    for name in msg.get_fields_and_field_types():
        value = getattr(msg, name)
        out[name] = fields(value) if hasattr(value, "get_fields_and_field_types") else value
    return out


def spin_until(node, done):
    deadline = time.monotonic() + WAIT_S
    while not done() and time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.05)
    return done()


def main() -> None:
    action, type_name, goal_json = sys.argv[1:4]
    package, kind, name = type_name.split("/")
    action_type = getattr(importlib.import_module(f"{package}.{kind}"), name)
    rclpy.init()
    node = rclpy.create_node("send_goal")
    client = ActionClient(node, action_type, action)
    out = {"accepted": False, "feedback": [], "status": None, "result": None}
    if spin_until(node, client.server_is_ready):
        goal = action_type.Goal(**json.loads(goal_json))
        sent = client.send_goal_async(
            goal, feedback_callback=lambda msg: out["feedback"].append(fields(msg.feedback))
        )
        spin_until(node, sent.done)
        handle = sent.result()
        out["accepted"] = bool(handle is not None and handle.accepted)
        if out["accepted"]:
            answer = handle.get_result_async()
            spin_until(node, answer.done)
            out["status"] = answer.result().status
            out["result"] = fields(answer.result().result)
    print(json.dumps(out), flush=True)
    client.destroy()
    node.destroy_node()
    rclpy.shutdown()


if __name__ == "__main__":
    main()
