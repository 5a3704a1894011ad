"""The weather node and its message conversion: the only modules touching ROS types."""
