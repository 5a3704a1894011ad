"""The wire format: per-valid-time slices of a canonical dataset and their 16-bit packing
(ROS-free; `ros.convert` turns them into messages)."""
