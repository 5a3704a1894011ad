"""ROS adapters of the display: the node, its message conversions and its Fast DDS profile."""
