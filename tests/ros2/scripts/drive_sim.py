"""A plain rclpy client that knows nothing of amiro: reads /scan, /odom, /map, drives /cmd_vel.

Prints one JSON line: what it received and how far the robot moved.
"""

import json
import math
import sys
import time

import rclpy
from geometry_msgs.msg import Twist
from nav_msgs.msg import OccupancyGrid, Odometry
from rclpy.qos import DurabilityPolicy, QoSProfile
from sensor_msgs.msg import LaserScan


def main() -> None:
    rclpy.init()
    node = rclpy.create_node("plain_driver")
    got = {"scan": 0, "odom": 0, "map": 0, "beams": 0, "scan_frame": "", "odom_frames": []}
    poses = []

    def on_scan(msg: LaserScan) -> None:
        got["scan"] += 1
        got["beams"] = len(msg.ranges)
        got["scan_frame"] = msg.header.frame_id

    def on_odom(msg: Odometry) -> None:
        got["odom"] += 1
        got["odom_frames"] = [msg.header.frame_id, msg.child_frame_id]
        poses.append((msg.pose.pose.position.x, msg.pose.pose.position.y))

    def on_map(msg: OccupancyGrid) -> None:
        got["map"] += 1

    node.create_subscription(LaserScan, "/scan", on_scan, 10)
    node.create_subscription(Odometry, "/odom", on_odom, 10)
    latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    node.create_subscription(OccupancyGrid, "/map", on_map, latched)
    cmd = node.create_publisher(Twist, "/cmd_vel", 10)
    deadline = time.monotonic() + 30
    while (not poses or not got["scan"] or not got["map"]) and time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.1)
    start = poses[-1] if poses else (0.0, 0.0)
    drive_until = time.monotonic() + float(sys.argv[1])
    while time.monotonic() < drive_until:
        twist = Twist()
        twist.angular.z = 0.5  # turn on the spot: safe wherever the robot stands
        twist.linear.x = 0.1
        cmd.publish(twist)
        end = time.monotonic() + 0.1
        while time.monotonic() < end:
            rclpy.spin_once(node, timeout_sec=0.02)
    end_pose = poses[-1] if poses else start
    got["moved_m"] = math.dist(start, end_pose)
    print(json.dumps(got), flush=True)
    node.destroy_node()
    rclpy.shutdown()


if __name__ == "__main__":
    main()
