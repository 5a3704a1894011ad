"""Write the display tests' plan fixtures with the real planner (run by hand, not by pytest).

    ros2_ws/.venv/bin/python src/shiproute_display/test/make_plan_fixtures.py

Three plans Busan -> Long Beach through the bundled March storm: the departure plan on cycle 1
(`storm_march`), the re-plan 24 h later from the first plan's position on cycle 2
(`storm_march_cycle2`) and the departure plan on the 20-member `storm_march_ensemble` under
CVaR 0.9 of fuel (with its spread: P10/P50/P90, probabilities, per-leg Hs and wind), each a
frozen `RoutePlan` written field by field (every waypoint) so
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
    ensemble = plan_voyage("Busan", "Long Beach", DEPART, RTA, "container_4600teu",
                           load_forecast("storm_march_ensemble"), budget_s=10.0,
                           cycle_id="storm_march_ensemble", risk="cvar:0.9")
    (DATA / "plan_ensemble.json").write_text(json.dumps(plan_dict(ensemble)))
    for p in (first, second, ensemble):
        print(p.plan_id, p.cycle_id, len(p.waypoints), round(p.total_fuel_t, 1), p.warnings)


if __name__ == "__main__":
    main()
