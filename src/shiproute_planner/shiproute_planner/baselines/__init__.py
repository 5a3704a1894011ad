"""Baseline route-finding methods judged by the planner's own evaluator, and the comparison.

`baselines.registry.baseline_methods` gives every one to the planner's method registry
(`shiproute_planner.methods`), so `shiproute plan --method <name>` runs it: isochrone,
dijkstra, astar, dijkstra_rpm, astar_rpm, ddp3, tc_astar, nsga2, spea2, pso, nsga2_seeded,
spea2_seeded, pso_seeded, nsga2_2obj.
"""
