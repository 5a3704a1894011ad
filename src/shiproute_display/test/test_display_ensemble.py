"""The display treats ensemble members as members, not as extra forecast times (issue 19 item 3):
valid times per member, one member's slice, the members' P90 of Hs per cell, each member's
Hs-peak track, and a plan's spread (P10/P50/P90, probabilities, per-leg Hs range) on the page."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from shiproute_display.forecast_view import HS_NAME, WIND_U_NAME, WIND_V_NAME, GridSpec, thin_slice
from shiproute_display.model import CycleInfo
from shiproute_display.state import DisplayState

GRID = GridSpec(30.0, 0.5, 20, 170.0, 0.5, 40)
T0 = 1_772_539_200.0  # 2026-03-03 12 UTC
STEP_S = 6 * 3600.0
MEMBERS, TIMES = 3, 4


def _peak(m: int, t: int) -> tuple[int, int]:
    """(row, column) where member m puts its highest sea at valid time t."""
    return 4 + 2 * m + t, 5 + 6 * t + m


def _fields(m: int, t: int) -> dict[str, np.ndarray]:
    hs = np.full((GRID.n_lat, GRID.n_lon), 1.0 + 0.5 * m, dtype=np.float32)
    hs[0, 0] = (1.0, 3.0, 2.0)[m]  # a cell where the members say 1, 3 and 2 m
    hs[_peak(m, t)] = 7.0 + m
    u = np.full(GRID.n_lat * GRID.n_lon, m + 1.0, dtype=np.float32)
    return {HS_NAME: hs.reshape(-1), WIND_U_NAME: u, WIND_V_NAME: np.zeros_like(u)}


def _state(complete: bool = True, announce_first: bool = True) -> DisplayState:
    st = DisplayState()
    info = CycleInfo("ens-1", T0, T0, T0 + (TIMES - 1) * STEP_S, STEP_S, MEMBERS * TIMES,
                     "unit-test", MEMBERS, ("control", "p1", "p2"), "ensemble")
    if announce_first:
        st.on_cycle(info)
    for m in range(MEMBERS):
        for t in range(TIMES):
            if not complete and (m, t) == (2, 3):
                continue
            st.on_slice("ens-1", thin_slice(m * TIMES + t, T0 + t * STEP_S, GRID, _fields(m, t),
                                            member=m))
    if not announce_first:  # separate topics: every slice may come before the announcement
        st.on_cycle(info)
    return st


def test_members_are_members_not_times() -> None:
    cyc = _state().snapshot()["forecast"]["cycles"][0]
    assert cyc["members"] == MEMBERS and cyc["slice_count"] == MEMBERS * TIMES
    assert cyc["times_s"] == [T0 + t * STEP_S for t in range(TIMES)]  # 4 times, not 12
    assert cyc["indices"] == list(range(TIMES)) and cyc["times_per_member"] == TIMES
    assert cyc["member_labels"] == ["control", "p1", "p2"]


def test_one_members_slice_and_the_members_p90() -> None:
    st = _state()
    one = json.loads(st.slice_json("ens-1", 2, "1") or b"null")
    assert one["member"] == 1 and one["valid_s"] == T0 + 2 * STEP_S
    hs = np.frombuffer(__import__("base64").b64decode(one["hs_b64"]), np.uint8)
    assert hs.reshape(GRID.n_lat, GRID.n_lon)[_peak(1, 2)] == 80  # 8.0 m in 0.1 m codes
    p90 = json.loads(st.slice_json("ens-1", 2, "p90") or b"null")
    codes = np.frombuffer(__import__("base64").b64decode(p90["hs_b64"]), np.uint8)
    # members 1, 3, 2 m: the P90 (linear, Hyndman-Fan 7) is 2 + 0.8 x (3 - 2) = 2.8 m
    assert codes[0] == 28
    # background 1.0, 1.5, 2.0 m: P90 = 1.5 + 0.8 x 0.5 = 1.9 m
    assert codes[GRID.n_lon * 10 + 30] == 19
    winds = np.array(p90["wind"]).reshape(-1, 4)
    np.testing.assert_allclose(winds[:, 2], 2.0)  # mean of 1, 2, 3 m/s
    assert st.slice_json("ens-1", TIMES, "0") is None  # no fifth valid time
    assert st.slice_json("ens-1", 0, str(MEMBERS)) is None  # no fourth member


def test_p90_of_a_partial_cycle_is_refused_and_tracks_wait() -> None:
    st = _state(complete=False)
    assert st.slice_json("ens-1", 3, "p90") is None  # member 2 lacks this time
    assert st.slice_json("ens-1", 2, "p90") is not None
    assert st.snapshot()["forecast"]["cycles"][0]["tracks"] == []


@pytest.mark.parametrize("announce_first", [True, False])
def test_each_members_hs_peak_track(announce_first: bool) -> None:
    tracks = _state(announce_first=announce_first).snapshot()["forecast"]["cycles"][0]["tracks"]
    assert len(tracks) == MEMBERS
    for m, track in enumerate(tracks):
        assert len(track) == TIMES
        for t, (lon, lat, valid_s, hs) in enumerate(track):
            row, col = _peak(m, t)
            assert (lat, lon) == pytest.approx((30.0 + 0.5 * row, 170.0 + 0.5 * col))
            assert valid_s == T0 + t * STEP_S and hs == pytest.approx(7.0 + m)


def test_ensemble_plan_spread_on_the_page() -> None:
    pytest.importorskip("rclpy")
    from display_fixtures import load_plan, plan_messages
    from shiproute_display.page_payload import plan_payload
    from shiproute_display.ros.convert import plan_from_msg

    rp = load_plan("plan_ensemble")  # the real planner on the 20-member storm, CVaR 0.9
    assert rp.ensemble_members == 20
    plan = plan_from_msg(plan_messages(rp, T0)[0])
    e = plan_payload(plan, None)["ensemble"]
    assert e["members"] == 20 and e["risk_measure"] == rp.risk_measure
    assert e["fuel_quantiles_t"] == [round(v, 1) for v in rp.fuel_quantiles_t]
    assert e["eta_quantiles_s"] == [round(v) for v in rp.eta_quantiles_s]
    assert e["fuel_quantiles_t"] == sorted(e["fuel_quantiles_t"])  # P10 <= P50 <= P90
    assert e["p_hs_violation"] == pytest.approx(rp.p_hs_violation, abs=5e-4)
    rows = plan_payload(plan, None)["schedule"]
    spread = {round(w.time_s): rp.leg_hs_spread_m[k] for k, w in enumerate(rp.waypoints[:-1])}
    checked = 0
    for r in rows:
        lo, _mid, hi = spread[round(r["start_s"])]
        if math.isfinite(lo):
            assert (r["hs_min_m"], r["hs_max_m"]) == (round(lo, 2), round(hi, 2))
            assert r["hs_min_m"] <= r["hs_max_m"]
            checked += 1
    assert checked >= len(rows) // 2  # most legs are sailed on the members
    assert plan_payload(plan_from_msg(plan_messages(load_plan("plan_cycle1"), T0)[0]),
                        None)["ensemble"] is None


def test_a_partial_deterministic_cycle_keeps_its_time_indices() -> None:
    st = DisplayState()
    st.on_cycle(CycleInfo("det-1", T0, T0, T0 + 5 * STEP_S, STEP_S, 6, "unit-test"))
    for t in (0, 1, 4):
        st.on_slice("det-1", thin_slice(t, T0 + t * STEP_S, GRID, _fields(0, t)))
    cyc = st.snapshot()["forecast"]["cycles"][0]
    assert cyc["indices"] == [0, 1, 4] and cyc["times_s"] == [T0 + t * STEP_S for t in (0, 1, 4)]
    assert json.loads(st.slice_json("det-1", 4) or b"null")["valid_s"] == T0 + 4 * STEP_S
