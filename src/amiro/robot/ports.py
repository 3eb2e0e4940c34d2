"""The bus topics of the robot port: what every robot adapter reads and writes.

The simulator, a ROS 2 robot and Pepper over NAOqi all offer these names with these types,
so the rest of amiro never knows which robot it drives.
"""

from __future__ import annotations

# robot -> amiro
SCAN = "/scan"  # LaserScan, frame "laser" at the base's centre
ODOM = "/odom"  # Odometry, odom -> base_footprint
TF = "/tf"  # TransformStamped, odom -> base_footprint
JOINT_STATES = "/joint_states"  # JointState, HeadYaw / HeadPitch
IMAGE = "/camera/image_raw"  # Image, rgb8
DEPTH = "/camera/depth/image_raw"  # Image, 32FC1 metres
CAMERA_INFO = "/camera/camera_info"  # CameraInfo

# amiro -> robot
CMD_VEL = "/cmd_vel"  # Twist, base frame
HEAD_CMD = "/amiro/head/cmd"  # JointState targets, HeadYaw / HeadPitch
SAY = "/amiro/say"  # SpeechRequest
DISPLAY = "/amiro/display"  # String: text, or a URL for a web view
POSTURE = "/amiro/posture"  # String: a posture name ("Stand", "Crouch")
EMERGENCY_STOP = "/amiro/emergency_stop"  # String: amiro.core.safety.estop_engaged reads it

HEAD_YAW, HEAD_PITCH = "HeadYaw", "HeadPitch"
