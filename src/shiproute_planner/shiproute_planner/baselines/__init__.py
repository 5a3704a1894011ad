"""Baseline route-finding methods judged by the planner's own evaluator, and the comparison.

Importing the package registers every method in `shiproute_planner.methods`, so
`shiproute plan --method <name>` runs it: isochrone, dijkstra, astar, dijkstra_rpm, astar_rpm,
ddp3, tc_astar, nsga2, spea2, pso, nsga2_seeded, spea2_seeded, pso_seeded, nsga2_2obj.
"""

from .registry import register_all

register_all()
