"""ISO 19030 cleaning rules on hand-made records whose answer is known."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_ais_replay.learning.cleaning import CleaningConfig, clean
from shiproute_ais_replay.learning.records import COLUMNS, Records
from shiproute_planner.learned.features import SEA_COLUMNS

N = 10  # records per block: one 10-minute segment at one record a minute


def _block(k: int, **over: np.ndarray | float) -> dict[str, np.ndarray]:
    """One steady 10-record segment (voyage k) with small alternating noise (every reading
    equally far from the mean: z = 1, never a Chauvenet outlier), then the overrides."""
    z = np.where(np.arange(N) % 2, 1.0, -1.0)
    t = 1.77e9 + k * 86400.0 + 60.0 * np.arange(N)
    c = {
        "time_s": t, "latitude_deg": np.full(N, 35.0),
        "longitude_deg": 160.0 + 0.005 * np.arange(N),
        "sog_kn": 17.0 + 0.05 * z, "cog_deg": np.full(N, 90.0),
        "heading_deg": 90.0 + 0.3 * z, "stw_kn": 17.0 + 0.05 * z,
        "shaft_rpm": 75.0 + 0.2 * z,
        "fuel_rate_t_per_h": 2.3 * (1 + 0.01 * z),
        "draft_fore_m": np.full(N, 11.5), "draft_aft_m": np.full(N, 12.5),
        "rudder_angle_deg": 0.3 * z, "water_depth_m": np.full(N, 4000.0),
        "voyage": np.full(N, float(k)),
    }
    for key, v in over.items():
        c[key] = np.broadcast_to(np.asarray(v, dtype=float), (N,)).copy()
    return c


def _run(blocks: list[dict], met_nan: np.ndarray | None = None, **cfg: float):
    cols = {c: np.concatenate([b[c] for b in blocks]) for c in COLUMNS}
    n = cols["time_s"].size
    met = {k: np.full(n, 0.0) for k in SEA_COLUMNS}
    met.update(wind_wave_hs_m=np.full(n, 1.0), wind_wave_period_s=np.full(n, 5.0),
               swell_period_s=np.full(n, 8.0))
    if met_nan is not None:
        for k in met:
            met[k][met_nan] = np.nan
    return clean(Records(cols, ("hand-made",)), met, CleaningConfig(breadth_m=37.5, **cfg))


def test_steady_segment_is_kept_whole_with_its_means() -> None:
    seg, rep = _run([_block(0, fuel_rate_t_per_h=np.linspace(2.2, 2.4, N))])
    assert rep["clean_segments"] == 1
    # evenly spread values: none is a Chauvenet outlier (max z = 1.57: N erfc(1.57/sqrt 2)
    # = 1.16 >= 0.5)
    assert rep["dropped_by_rule"]["chauvenet"] == 0
    assert seg["fuel_t_per_h"][0] == pytest.approx(2.3)


def test_chauvenet_removes_a_fuel_spike_and_recomputes_the_mean() -> None:
    fuel = np.full(N, 2.3) + np.linspace(-0.01, 0.01, N)
    fuel[4] = 6.9  # meter spike: 3x the reading
    seg, rep = _run([_block(0, fuel_rate_t_per_h=fuel)])
    assert rep["dropped_by_rule"]["chauvenet"] == 1
    assert rep["clean_segments"] == 1
    assert seg["fuel_t_per_h"][0] == pytest.approx(2.3, abs=0.01)  # spike gone from the mean


def test_manoeuvre_dropped_by_rpm_dispersion() -> None:
    rpm = 75.0 + 6.0 * np.sin(np.linspace(0, 2 * np.pi, N, endpoint=False))  # sigma 4.2 rpm
    _, rep = _run([_block(0), _block(1, shaft_rpm=rpm)])
    assert rep["segments_dropped_by_rule"]["rpm_std"] == 1
    assert rep["dropped_by_rule"]["rpm_std"] == N
    assert rep["clean_segments"] == 1


def test_rpm_dispersion_just_below_the_threshold_is_kept() -> None:
    rpm = 75.0 + 2.8 * np.sqrt(2) * np.sin(np.linspace(0, 2 * np.pi, N, endpoint=False))
    _, rep = _run([_block(1, shaft_rpm=rpm)])  # sigma 2.8 rpm < 3
    assert rep["segments_dropped_by_rule"]["rpm_std"] == 0


def test_speed_change_dropped_by_sog_dispersion() -> None:
    _, rep = _run([_block(2, sog_kn=np.linspace(15.0, 17.2, N))])  # sigma 0.70 kn > 0.5
    assert rep["segments_dropped_by_rule"]["sog_std"] == 1


def test_turn_dropped_by_heading_change_across_north() -> None:
    # 350 -> 14 deg: a 24-degree turn through north (circular statistics, 003 eq. 5 and 8)
    hdg = (350.0 + np.linspace(0.0, 24.0, N)) % 360.0
    _, rep = _run([_block(3, heading_deg=hdg)])
    assert rep["segments_dropped_by_rule"]["heading_change"] == 1
    # steady course through north (359/1 deg) is not a turn
    _, rep2 = _run([_block(3, heading_deg=np.where(np.arange(N) % 2, 359.5, 0.5))])
    assert rep2["segments_dropped_by_rule"]["heading_change"] == 0


def test_rudder_and_shallow_water_rules() -> None:
    _, rep = _run([_block(4, rudder_angle_deg=8.0), _block(5, water_depth_m=40.0),
                   _block(6)])
    assert rep["segments_dropped_by_rule"]["rudder"] == 1
    # 3 sqrt(B T) = 3 sqrt(37.5 x 12) = 63.6 m > 40 m: shallow (ISO 19030-2 / ITTC)
    assert rep["segments_dropped_by_rule"]["shallow_water"] == 1
    assert rep["clean_segments"] == 1


def test_record_rules_incomplete_stuck_not_under_way_no_met() -> None:
    b0 = _block(7)
    b0["fuel_rate_t_per_h"][3] = np.nan
    b1 = _block(8, shaft_rpm=74.87)  # frozen RPM sensor: 10 identical readings
    b2 = _block(9, shaft_rpm=0.0, sog_kn=0.1)
    seg, rep = _run([b0, b1, b2, _block(10)], met_nan=np.arange(30, 40))
    d = rep["dropped_by_rule"]
    assert d["incomplete"] == 1
    assert d["stuck_value"] == N
    assert d["not_under_way"] == N
    assert d["no_met"] == N
    assert rep["clean_segments"] == 1  # block 7 keeps 9 records, blocks 8-10 are gone
    assert seg["n_records"][0] <= 9


def test_short_segment_and_stw_from_sog_minus_current() -> None:
    short = {k: v[:3] for k, v in _block(11).items()}
    b = _block(12, stw_kn=np.nan)
    seg, rep = _run([short, b])
    assert rep["segments_dropped_by_rule"]["short_segment"] == 1
    # no log: STW = |ground velocity - current|, here no current so STW = SOG
    assert seg["stw_kn"][0] == pytest.approx(seg["sog_kn"][0], rel=1e-6)
    assert rep["stw_source"]["sog_minus_forecast_current"] == N
