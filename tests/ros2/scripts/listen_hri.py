"""A plain rclpy ROS4HRI subscriber that knows nothing of amiro.

Usage: listen_hri.py SECONDS.  Listens to /humans/persons/tracked, /humans/bodies/tracked
(hri_msgs/IdsList) and /tf until a person has been tracked with her person_<id> frame and
her name for a few messages, or SECONDS pass.  Prints one JSON line: the person and body
ids seen, per person her last frame position, name, face_id and location_confidence.
"""

import json
import sys
import time

import rclpy
from hri_msgs.msg import IdsList
from rclpy.qos import DurabilityPolicy, QoSProfile
from std_msgs.msg import Float32, String
from tf2_msgs.msg import TFMessage


def main() -> None:
    wait_s = float(sys.argv[1])
    rclpy.init()
    node = rclpy.create_node("plain_hri_listener")
    latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    seen = {"persons": [], "bodies": [], "frames": {}, "people": {}, "tracked_msgs": 0}

    def listen(pid):
        entry = seen["people"].setdefault(pid, {})
        for field, kind in (
            ("name", String),
            ("face_id", String),
            ("location_confidence", Float32),
        ):
            node.create_subscription(
                kind,
                f"/humans/persons/{pid}/{field}",
                lambda msg, f=field: entry.__setitem__(f, msg.data),
                latched,
            )

    def on_persons(msg):
        seen["tracked_msgs"] += 1
        for pid in msg.ids:
            if pid not in seen["persons"]:
                seen["persons"].append(pid)
                listen(pid)

    def on_bodies(msg):
        seen["bodies"] = sorted(set(seen["bodies"]) | set(msg.ids))

    def on_tf(msg):
        for t in msg.transforms:
            if t.child_frame_id.startswith(("person_", "body_")):
                v = t.transform.translation
                seen["frames"][t.child_frame_id] = [t.header.frame_id, v.x, v.y, v.z]

    node.create_subscription(IdsList, "/humans/persons/tracked", on_persons, 10)
    node.create_subscription(IdsList, "/humans/bodies/tracked", on_bodies, 10)
    node.create_subscription(TFMessage, "/tf", on_tf, 100)

    def enough():
        named = [p for p, e in seen["people"].items() if len(e) == 3 and e["name"]]
        return any(f"person_{p}" in seen["frames"] for p in named) and seen["tracked_msgs"] >= 3

    deadline = time.monotonic() + wait_s
    while not enough() and time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.1)
    print(json.dumps(seen))
    node.destroy_node()
    rclpy.shutdown()


if __name__ == "__main__":
    main()
