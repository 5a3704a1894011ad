"""No-go zones in planning: a hard zone across the great circle is sailed round, a penalty
zone is avoided when its penalty outweighs the detour and crossed when it does not."""

from __future__ import annotations

import json
from datetime import timedelta

import numpy as np
import shapely
from shiproute_core.geodesy import densify_track
from shiproute_planner.planning import plan_voyage

BOX = [[-8.0, 45.5], [-7.0, 45.5], [-7.0, 46.5], [-8.0, 46.5], [-8.0, 45.5]]  # Bay of Biscay


def _zones(tmp_path, mode: str, penalty: float = 0.0):
    path = tmp_path / f"{mode}.geojson"
    path.write_text(json.dumps({"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {"name": "exercise", "mode": mode,
                                           "penalty_per_nm": penalty},
         "geometry": {"type": "Polygon", "coordinates": [BOX]}}]}))
    return path


def _nm_inside(plan) -> float:
    lon, lat, _ = plan.track()
    d_lon, d_lat = densify_track(lon, lat, 185.2)  # every 0.1 NM
    return float(shapely.contains_xy(shapely.Polygon(BOX), d_lon, d_lat).sum()) * 0.1


def _plan(land_mask, **kw):
    return plan_voyage("46.0,-10.0", "46.0,-5.0", "2026-06-01T00:00Z", timedelta(hours=26),
                       "container_4600teu", approach_nm=0, land=land_mask, budget_s=60.0,
                       max_generations=30, stage_hours=3.0, default_bathymetry=False, **kw)


def test_hard_zone_is_sailed_round(land_mask, tmp_path):
    free = _plan(land_mask)
    assert _nm_inside(free) > 30  # premise: the straight route crosses the 38-NM-wide box
    plan = _plan(land_mask, zones=[_zones(tmp_path, "hard")])
    assert plan.feasible, plan.infeasible_reasons
    assert _nm_inside(plan) == 0.0
    assert any("1 hard" in w for w in plan.warnings)
    assert plan.total_distance_nm > free.total_distance_nm


def test_penalty_zone_weighs_against_the_detour(land_mask, tmp_path):
    cheap = _plan(land_mask, zones=[_zones(tmp_path, "penalty", 0.0)])
    dear = _plan(land_mask, zones=[_zones(tmp_path, "penalty", 5.0)])  # 5 t per NM inside
    assert cheap.feasible and dear.feasible
    assert _nm_inside(cheap) > 30 and _nm_inside(dear) == 0.0
    assert any("avoid-if-possible zone" in w for w in cheap.warnings)
    assert np.isfinite(dear.total_fuel_t)
