"""ROS 2 bridge: the bus over DDS, standard message types, split deployments and launch."""
