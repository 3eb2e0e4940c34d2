"""Recording runs to MCAP with ROS 2 message schemas, and replaying them into the bus."""
