"""rosbag2 MCAP I/O: type store, tolerant reader and scanner, writer, ShipState records."""
