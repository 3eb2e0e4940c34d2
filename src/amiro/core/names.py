"""Every bus name amiro uses, in one place: topics, services and actions.

Modules import these constants instead of writing literals, so a name is changed (or remapped
for a robot profile) in one place and a typo is an import error, not a silent dead topic.
The ROS 2 bridge carries the same names over DDS (CONTRACTS.md section 5).  Message types
are named beside each topic; the core ones are :mod:`amiro.core.messages` dataclasses.
"""

from __future__ import annotations

# --- robot port: what every robot adapter (sim, ROS 2, NAOqi) offers --------------------
SCAN = "/scan"  # LaserScan, frame "laser" at the base's centre
ODOM = "/odom"  # Odometry, odom -> base_footprint
TF = "/tf"  # TransformStamped
TF_STATIC = "/tf_static"  # TransformStamped, latched
JOINT_STATES = "/joint_states"  # JointState, HeadYaw / HeadPitch
IMAGE = "/camera/image_raw"  # Image, rgb8
DEPTH = "/camera/depth/image_raw"  # Image, 32FC1 metres
CAMERA_INFO = "/camera/camera_info"  # CameraInfo
CMD_VEL = "/cmd_vel"  # Twist, base frame: written only by the velocity multiplexer
# the multiplexer's inputs (Twist), most urgent first: robot.velocity_mux picks one
CMD_VEL_TELEOP = "/amiro/cmd_vel/teleop"  # an operator's joystick or dashboard
CMD_VEL_NAVIGATION = "/amiro/cmd_vel/navigation"  # MoveTo
CMD_VEL_PRIMITIVES = "/amiro/cmd_vel/primitives"  # forward / rotate (RecognizeActivity reframing)
HEAD_CMD = "/amiro/head/cmd"  # JointState targets, HeadYaw / HeadPitch
SAY = "/amiro/say"  # SpeechRequest
DISPLAY = "/amiro/display"  # String: text, or a URL for a web view
POSTURE = "/amiro/posture"  # String: a posture name ("Stand", "Crouch")
EMERGENCY_STOP = "/amiro/emergency_stop"  # String: see core.safety.estop_engaged
CLOCK = "/clock"  # rosgraph_msgs/Clock over ROS 2
MAP = "/map"  # OccupancyGrid, latched
GOAL_POSE = "/goal_pose"  # PoseStamped: a navigation goal from RViz

HEAD_YAW, HEAD_PITCH = "HeadYaw", "HeadPitch"

# --- navigation ---------------------------------------------------------------------------
INITIAL_POSE = "/initialpose"  # PoseStamped
LOCALIZATION = "/amiro/localization/pose"  # PoseStamped, map frame
GROUND_TRUTH = "/amiro/sim/ground_truth"  # PoseStamped: the simulator's true pose
COLLISION = "/amiro/sim/collision"  # Collision: the simulated base touched something
SLAM_POSE = "/amiro/slam/pose"  # PoseStamped
PATH = "/amiro/navigation/path"  # Path: the planned path
GLOBAL_LOCALIZATION = "/global_localization"  # service, as ROS amcl's std_srvs/Empty
MOVE_TO = "/amiro/navigation/move_to"  # action: MoveToGoal -> MoveToResult
# ROS 2 only: MoveTo as Nav2's nav2_msgs/action/NavigateToPose (served, or called on a Nav2 robot)
NAVIGATE_TO_POSE = "/navigate_to_pose"
# ROS 2 only: a Nav2 robot's behaviour server (nav2_msgs Spin, BackUp, DriveOnHeading), which
# navigation.backend nav2 calls for the primitives where the robot offers them
NAV2_SPIN = "/spin"
NAV2_BACKUP = "/backup"
NAV2_DRIVE_ON_HEADING = "/drive_on_heading"
FORWARD = "/amiro/navigation/forward"  # action: drive straight a distance
ROTATE = "/amiro/navigation/rotate"  # action: turn in place by an angle

# --- perception and activity --------------------------------------------------------------
PEOPLE = "/amiro/people"  # String (JSON): the people tracked
HRI_PEOPLE = "/amiro/hri/people"  # People: another stack's ROS4HRI persons (perception hri)
OBSERVATIONS = "/amiro/sim/observations"  # CameraObservations from the simulated head
SKELETONS = "/amiro/sim/skeletons"  # Skeleton

# --- dialogue -----------------------------------------------------------------------------
HEARD = "/amiro/speech/heard"  # SpeechHeard
AUDIO = "/amiro/audio"  # AudioStamped: the robot's microphone (audio_common_msgs/AudioStamped)
UNDERSTAND = "/amiro/dialogue/understand"  # service: text -> intent and entities

# --- smart environment and health ---------------------------------------------------------
SENSORS = "/amiro/env/sensors"  # SensorReading
NOTIFICATIONS = "/amiro/notifications"  # Notification
ACK = "/amiro/notifications/ack"  # Acknowledgement
HEALTH = "/amiro/env/health"  # HealthMeasurement
DEVICE_COMMAND = "/amiro/env/devices/set"  # DeviceCommand
DEVICE_STATE = "/amiro/env/devices/state"  # DeviceState

# --- behaviour ----------------------------------------------------------------------------
EVENTS = "/amiro/events"  # BehaviorEvent
BEHAVIOR_RUN = "/amiro/behavior/run"  # action: run a behaviour by kind
SEARCH = "/amiro/behavior/search"  # action: the Search task on its own
RECOGNIZE_ACTIVITY = "/amiro/behavior/recognize_activity"  # action: RecognizeActivity alone
HEARTBEAT = "/amiro/heartbeat"  # String: a split deployment's liveness
