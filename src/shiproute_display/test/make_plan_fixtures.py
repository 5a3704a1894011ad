"""Write the display tests' plan fixtures with the real planner (run by hand, not by pytest).

    ros2_ws/.venv/bin/python src/shiproute_display/test/make_plan_fixtures.py

Two plans Busan -> Long Beach through the bundled March storm: the departure plan on cycle 1
(`storm_march`) and the re-plan 24 h later from the first plan's position on cycle 2
(`storm_march_cycle2`), each a frozen `RoutePlan` written field by field (every waypoint) so
the tests publish it through the planner's own `plan_to_msg` / `plan_to_rpm_profile`.
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

DATA = Path(__file__).resolve().parents[1] / "shiproute_display" / "sample_plans"
DEPART = "2026-03-03T18:00:00Z"
RTA = "2026-03-16T18:00:00Z"


def plan_dict(plan) -> dict:
    """RoutePlan -> JSON-able dict (NaN kept as the string 'nan' by json's default)."""
    d = dataclasses.asdict(plan)
    d.pop("extra", None)
    return d


def main() -> None:
    from shiproute_display.geometry import position_at
    from shiproute_display.model import Plan, Waypoint
    from shiproute_planner.plan_setup import load_forecast
    from shiproute_planner.planning import plan_voyage

    DATA.mkdir(exist_ok=True)
    first = plan_voyage("Busan", "Long Beach", DEPART, RTA, "container_4600teu",
                        load_forecast("storm_march"), budget_s=3.0, cycle_id="storm_march")
    (DATA / "plan_cycle1.json").write_text(json.dumps(plan_dict(first)))
    t = first.departure_s + 24 * 3600.0
    view = Plan(first.plan_id, "", "", "", "", "", 0, 0, 0, 0, True, (), (), 0, 0, 0, 0,
                tuple(Waypoint(w.lat_deg, w.lon_deg, w.time_s, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0)
                      for w in first.waypoints))
    lat, lon, _ = position_at(view, t)
    second = plan_voyage("Busan", "Long Beach", DEPART, RTA, "container_4600teu",
                         load_forecast("storm_march_cycle2"), budget_s=3.0,
                         previous_plan=first, position=(lat, lon, t),
                         cycle_id="storm_march_cycle2")
    (DATA / "plan_cycle2.json").write_text(json.dumps(plan_dict(second)))
    for p in (first, second):
        print(p.plan_id, p.cycle_id, len(p.waypoints), round(p.total_fuel_t, 1), p.warnings)


if __name__ == "__main__":
    main()
