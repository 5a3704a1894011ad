"""Network inputs of the learned model and the ship file's physics prior for them.

Inputs follow reference 003 (speed, fore and aft draft, wind speed, relative wind direction,
wave height, relative wave direction), with the drafts as mean draft and trim and the
directions as cosines of the angle off the bow (0 deg = head on), plus the mean wave period
the forecast gives. The course itself is not an input: it enters through the relative
directions, and alone it only names the route. Speed is the speed through water.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json

import numpy as np
import numpy.typing as npt
from shiproute_core.units import M_S_PER_KNOT

from ..ship.condition import at_drafts
from ..ship.fast import fast_model
from ..ship.physics import relative_wave_deg
from ..ship.seastate import SeaState
from ..ship.spec import ShipSpec

FEATURES = ("stw_kn", "draft_mean_m", "trim_m", "wind_speed_m_s", "cos_rel_wind",
            "hs_m", "cos_rel_wave", "wave_period_s")
SEA_COLUMNS = ("wind_u_m_s", "wind_v_m_s", "wind_wave_hs_m", "wind_wave_from_deg",
               "wind_wave_period_s", "swell_hs_m", "swell_from_deg", "swell_period_s",
               "current_u_m_s", "current_v_m_s")
#: columns a segment table (dict of equal-length arrays) must hold
SEGMENT_COLUMNS = ("time_s", "voyage", "stw_kn", "heading_deg", "draft_fore_m", "draft_aft_m",
                   *SEA_COLUMNS, "rpm", "fuel_t_per_h")


def ship_identity(ship: ShipSpec) -> str:
    """sha256 of the hull, propeller, engine and windage data: the ship, whatever its load."""
    parts = {k: dataclasses.asdict(getattr(ship, k))
             for k in ("hull", "propeller", "engine", "windage")}
    text = json.dumps({"name": ship.name, **parts}, sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()


def sea_of(columns: dict[str, np.ndarray]) -> SeaState:
    """SeaState of the segments (or legs) in ``columns``."""
    return SeaState.from_arrays(**{k: np.asarray(columns[k], dtype=float) for k in SEA_COLUMNS})


def feature_matrix(stw_kn: npt.ArrayLike, heading_deg: npt.ArrayLike,
                   draft_fore_m: npt.ArrayLike, draft_aft_m: npt.ArrayLike,
                   sea: SeaState) -> np.ndarray:
    """(n, len(FEATURES)) inputs; arrays broadcast to one 1-D shape."""
    stw_kn = np.asarray(stw_kn, dtype=float)
    n = np.broadcast_shapes(stw_kn.shape, np.shape(heading_deg), sea.shape())
    s = sea.broadcast(n)
    hdg = np.broadcast_to(np.asarray(heading_deg, dtype=float), n)
    wind_from = np.degrees(np.arctan2(-s.wind_u_m_s, -s.wind_v_m_s))
    e_ws, e_sw = s.wind_wave_hs_m**2, s.swell_hs_m**2
    ang_ws, ang_sw = np.radians(s.wind_wave_from_deg), np.radians(s.swell_from_deg)
    wave_from = np.degrees(np.arctan2(e_ws * np.sin(ang_ws) + e_sw * np.sin(ang_sw),
                                      e_ws * np.cos(ang_ws) + e_sw * np.cos(ang_sw)))
    e = e_ws + e_sw
    period = np.where(e > 0, (e_ws * s.wind_wave_period_s + e_sw * s.swell_period_s)
                      / np.maximum(e, 1e-12), 0.0)
    fore = np.broadcast_to(np.asarray(draft_fore_m, dtype=float), n)
    aft = np.broadcast_to(np.asarray(draft_aft_m, dtype=float), n)
    cols = [np.broadcast_to(stw_kn, n), 0.5 * (fore + aft), aft - fore, s.wind_speed_m_s,
            np.cos(np.radians(relative_wave_deg(hdg, wind_from))), s.hs_m,
            np.cos(np.radians(relative_wave_deg(hdg, wave_from))), period]
    return np.column_stack([np.asarray(c, dtype=float).reshape(-1) for c in cols])


DRAFT_STEP_M = 0.1  # drafts are rounded to this for the prior (one table set per pair)


def physics_prior(ship: ShipSpec, stw_kn: np.ndarray, heading_deg: np.ndarray, sea: SeaState,
                  draft_fore_m: np.ndarray | float | None = None,
                  draft_aft_m: np.ndarray | float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(rpm, fuel t/h) the ship file's model needs for ``stw_kn`` in ``sea`` at the given
    drafts (rounded to DRAFT_STEP_M; None = the file's): the prior the network corrects
    (tabulated model, within 0.5 % of the direct physics solve)."""
    v = np.maximum(np.asarray(stw_kn, dtype=float), 0.5) * M_S_PER_KNOT
    n = v.size
    hdg = np.broadcast_to(np.asarray(heading_deg, dtype=float), (n,))
    sea = sea.broadcast((n,))
    c = ship.condition
    fore = np.broadcast_to(np.asarray(c.draft_fore_m if draft_fore_m is None else draft_fore_m,
                                      dtype=float), (n,))
    aft = np.broadcast_to(np.asarray(c.draft_aft_m if draft_aft_m is None else draft_aft_m,
                                     dtype=float), (n,))
    key = np.round(np.column_stack([fore, aft]) / DRAFT_STEP_M).astype(np.int64)
    rpm, fuel = np.empty(n), np.empty(n)
    groups, inverse = np.unique(key, axis=0, return_inverse=True)
    for g, (kf, ka) in enumerate(groups):
        idx = np.flatnonzero(inverse.reshape(-1) == g)
        fm = fast_model(at_drafts(ship, round(kf * DRAFT_STEP_M, 3), round(ka * DRAFT_STEP_M, 3)))
        s = sea.take(idx)
        r = np.clip(fm.rpm_for_speed(v[idx], hdg[idx], s), 1.0, 1.45 * ship.engine.rpm_max)
        rpm[idx] = r
        fuel[idx] = fm.evaluate(r, hdg[idx], s).fuel_t_per_h
    return rpm, fuel
