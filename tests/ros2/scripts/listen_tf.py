"""A plain rclpy client that knows nothing of amiro: listens to /tf, /tf_static and /odom.

It turns the robot on /cmd_vel so the transforms move, then prints one JSON line: the
(parent, child) edges seen on each topic, how many odom -> base_footprint transforms had an
/odom message of the same stamp, and the largest difference between the two.  When some
process publishes map -> odom, also how far map -> odom -> base_footprint lands from the
simulator's ground truth (``/amiro/sim/ground_truth``).
"""

import json
import math
import sys
import time

import rclpy
from geometry_msgs.msg import PoseStamped, Twist
from nav_msgs.msg import Odometry
from rclpy.qos import DurabilityPolicy, QoSProfile
from tf2_msgs.msg import TFMessage


def stamp_ns(header) -> int:
    return header.stamp.sec * 1_000_000_000 + header.stamp.nanosec


def yaw(q) -> float:
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def localization_error(latest: dict) -> float | None:
    """Distance between map -> odom -> base_footprint and the ground truth."""
    map_odom, odom_base = latest.get(("map", "odom")), latest.get(("odom", "base_footprint"))
    truth = latest.get("truth")
    if map_odom is None or odom_base is None or truth is None:
        return None
    th = yaw(map_odom.rotation)
    ox, oy = odom_base.translation.x, odom_base.translation.y
    x = map_odom.translation.x + math.cos(th) * ox - math.sin(th) * oy
    y = map_odom.translation.y + math.sin(th) * ox + math.cos(th) * oy
    return math.hypot(x - truth.position.x, y - truth.position.y)


def main() -> None:
    seconds = float(sys.argv[1])
    rclpy.init()
    node = rclpy.create_node("plain_tf_listener")
    edges = {"/tf": set(), "/tf_static": set()}
    static = {}
    odom_by_stamp = {}
    odom_tfs = []
    latest = {}  # (parent, child) or "truth" -> the last transform or pose

    def on_tf(topic, msg: TFMessage) -> None:
        for t in msg.transforms:
            edges[topic].add((t.header.frame_id, t.child_frame_id))
            latest[(t.header.frame_id, t.child_frame_id)] = t.transform
            if topic == "/tf_static":
                tr = t.transform.translation
                static[t.child_frame_id] = [tr.x, tr.y, tr.z]
            elif (t.header.frame_id, t.child_frame_id) == ("odom", "base_footprint"):
                odom_tfs.append(t)

    def on_odom(msg: Odometry) -> None:
        odom_by_stamp[stamp_ns(msg.header)] = msg.pose.pose

    node.create_subscription(TFMessage, "/tf", lambda m: on_tf("/tf", m), 100)
    latched = QoSProfile(depth=100, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    node.create_subscription(TFMessage, "/tf_static", lambda m: on_tf("/tf_static", m), latched)
    node.create_subscription(Odometry, "/odom", on_odom, 100)
    node.create_subscription(
        PoseStamped, "/amiro/sim/ground_truth", lambda m: latest.update(truth=m.pose), 10
    )
    cmd = node.create_publisher(Twist, "/cmd_vel", 10)
    deadline = time.monotonic() + 30
    while not (odom_tfs and edges["/tf_static"]) and time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.1)
    drive_until = time.monotonic() + seconds
    while time.monotonic() < drive_until:
        twist = Twist()
        twist.angular.z = 0.5  # turn on the spot: safe wherever the robot stands
        twist.linear.x = 0.1
        cmd.publish(twist)
        end = time.monotonic() + 0.1
        while time.monotonic() < end:
            rclpy.spin_once(node, timeout_sec=0.02)
    settle = time.monotonic() + 1.0  # the base stops once commands stop
    while time.monotonic() < settle:
        rclpy.spin_once(node, timeout_sec=0.02)
    matched, worst, moved = 0, 0.0, 0.0
    for t in odom_tfs:
        pose = odom_by_stamp.get(stamp_ns(t.header))
        if pose is None:
            continue
        matched += 1
        tr = t.transform.translation
        moved = max(moved, math.hypot(tr.x, tr.y))
        worst = max(
            worst,
            abs(tr.x - pose.position.x),
            abs(tr.y - pose.position.y),
            abs(yaw(t.transform.rotation) - yaw(pose.orientation)),
        )
    result = {
        "tf": sorted(edges["/tf"]),
        "tf_static": sorted(edges["/tf_static"]),
        "static_translation": static,
        "odom_tf": len(odom_tfs),
        "matched": matched,
        "worst_difference": worst,
        "moved_m": moved,
        "localization_error_m": localization_error(latest),
    }
    print(json.dumps(result), flush=True)
    node.destroy_node()
    rclpy.shutdown()


if __name__ == "__main__":
    main()
