"""ROS 2 transport: the bus over DDS (topics, services, actions), standard message
conversion, contexts and domains, and the interface packages built at setup.  Deployment
roles live in :mod:`amiro.deploy`."""
