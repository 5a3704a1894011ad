"""The planner's ROS adapter: the node, message conversion, forecast-cycle intake, the re-plan
trigger and process tuning. Only this room imports rclpy; nothing outside it imports it."""
