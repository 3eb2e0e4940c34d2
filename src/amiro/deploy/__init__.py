"""Split deployments: robot, edge and cloud processes over ROS 2, their launch, health and
ledgers, built with the same assembly functions as the embedded system (:mod:`amiro.system`)."""
