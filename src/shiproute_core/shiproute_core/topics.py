"""Topic, service and action names of the shiproute graph, defined once for nodes, tools and
tests (integrators subscribe to these)."""

from __future__ import annotations

# weather node
FORECAST_SLICES = "/shiproute/forecast/slices"
FORECAST_CYCLE = "/shiproute/forecast/cycle"
FORECAST_LOAD = "/shiproute/forecast/load"
# replay node and recorded bags
SHIP_STATE = "/shiproute/ship_state"
OWN_FIX = "/shiproute/fix"
# planner node
PLAN_ROUTE = "/shiproute/plan/route"
PLAN_RPM_PROFILE = "/shiproute/plan/rpm_profile"
PLAN_PATH = "/shiproute/plan/path"
PLANNER_SET_VOYAGE = "/shiproute/planner/set_voyage"
PLANNER_PLAN_ACTION = "/shiproute/planner/plan"
# bridge display (Foxglove-ready topics)
DISPLAY_GEOJSON = "/shiproute/display/geojson"
DISPLAY_SHIP_FIX = "/shiproute/display/ship_fix"
DISPLAY_PLAN_FIX = "/shiproute/display/plan_fix"
DISPLAY_PLANNED_RPM = "/shiproute/display/planned_rpm"
# ROS-wide
DIAGNOSTICS = "/diagnostics"
