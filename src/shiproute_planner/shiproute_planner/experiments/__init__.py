"""Experiments apart from the product: the method comparison (every method on one voyage,
tables, plots) and the benchmark scripts. The planner never imports this room."""
