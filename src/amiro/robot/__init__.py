"""The robot port and its adapters: the simulator, any ROS 2 robot, Pepper over NAOqi.

Every adapter gives the rest of amiro the same bus topics the in-process simulator does
(``/scan``, ``/odom``, ``/tf``, ``/joint_states`` in; ``/cmd_vel``, ``/amiro/head/cmd``,
``/amiro/say``, ``/amiro/display`` out), so navigation and behaviours run unchanged.
"""
