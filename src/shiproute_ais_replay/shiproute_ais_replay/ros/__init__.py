"""ROS adapters: the replay node, the recorder and the message conversions (rclpy only here)."""
