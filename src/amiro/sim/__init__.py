"""The simulated apartment, the robot body and sensors, and the residents."""
