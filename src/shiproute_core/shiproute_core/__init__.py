"""What every shiproute package shares and defines once: units, geodesy, names and flags.

Plain Python without ROS, so libraries, nodes and tests all read the same definitions.
"""
