"""Generate the gridded fields of a scenario: wind, wind sea, swell, total sea, currents."""

from __future__ import annotations

import numpy as np
from shiproute_core.units import S_PER_HOUR

from ..contract import canonical as cv
from ..physics.fetch import direction_bin, fetch_by_direction_m
from ..physics.landmask import sea_mask
from ..physics.wave_growth import grow_step, jonswap_tm01_over_tp
from .swell import distances_and_bearings, radiate
from .synth_currents import steady_currents, with_wind_drift
from .synth_seas import BackgroundSwell, background_swell, combine
from .synth_wind import Season, TrackPoint, total_wind, track_at, translation_m_s, wave_phases

SPIN_UP_STEPS = 8
WIND_SEA_GAMMA = 3.3


def _wind_series(season: Season, track: list[TrackPoint], phases: np.ndarray, lat: np.ndarray,
                 lon: np.ndarray, hours: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    lat_g, lon_g = np.meshgrid(lat, lon, indexing="ij")
    shape = (hours.size, lat.size, lon.size)
    u, v = np.empty(shape), np.empty(shape)
    for i, h in enumerate(hours):
        u[i], v[i] = total_wind(season, track, phases, float(h), lat_g, lon_g)
    return u, v


def _wind_sea(u: np.ndarray, v: np.ndarray, fetch: np.ndarray,
              dt_s: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """March the equivalent-duration growth through time (with a spin-up on the first wind)."""
    speed = np.hypot(u, v)
    from_deg = np.rad2deg(np.arctan2(-u, -v)) % 360.0
    hs = np.zeros(u.shape)
    tp = np.zeros(u.shape)
    h = np.zeros(u.shape[1:])
    d = from_deg[0].copy()
    for i in range(-SPIN_UP_STEPS, u.shape[0]):
        k = max(i, 0)
        f = np.take_along_axis(fetch, direction_bin(from_deg[k])[None], axis=0)[0]
        h, t = grow_step(h, d, speed[k], from_deg[k], f, dt_s)
        d = from_deg[k]
        if i >= 0:
            hs[i], tp[i] = h, t
    return hs, tp, from_deg


def _storm_sources(track: list[TrackPoint], hours: np.ndarray, hs: np.ndarray, tp: np.ndarray,
                   lat: np.ndarray, lon: np.ndarray) -> np.ndarray:
    """Per storm time: (hour, lat, lon, source Hs, source Tp, heading deg, radius m)."""
    rows = []
    lat_g, lon_g = np.meshgrid(lat, lon, indexing="ij")
    for i, h in enumerate(hours):
        p = track_at(track, float(h))
        if p is None:
            continue
        r_km = np.hypot((lon_g - p.lon_deg) * 111.2 * np.cos(np.deg2rad(lat_g)),
                        (lat_g - p.lat_deg) * 111.2)
        core = (r_km < 2.0 * p.rmax_km) & np.isfinite(hs[i])
        if not core.any():
            continue
        k = np.argmax(np.where(core, hs[i], -1.0))
        ue, vn = translation_m_s(track, float(h))
        heading = float(np.rad2deg(np.arctan2(ue, vn)) % 360.0)
        rows.append([h, p.lat_deg, p.lon_deg, hs[i].flat[k], tp[i].flat[k], heading,
                     2.0 * p.rmax_km * 1e3])
    return np.array(rows, dtype=np.float64).reshape(-1, 7)


def build_fields(season: Season, swell: BackgroundSwell, track: list[TrackPoint],
                 rng: np.random.Generator, lat: np.ndarray, lon: np.ndarray,
                 hours: np.ndarray) -> dict[str, np.ndarray]:
    """All canonical fields (time, lat, lon) for hours since the scenario epoch."""
    phases = wave_phases(rng)
    sea = sea_mask(lat, lon, float(lat[1] - lat[0]))
    u, v = _wind_series(season, track, phases, lat, lon, hours)
    dt_s = float(hours[1] - hours[0]) * S_PER_HOUR
    fetch = fetch_by_direction_m(sea, lat, lon)
    ws_hs, ws_tp, ws_dir = _wind_sea(u, v, fetch, dt_s)
    ws_tm = ws_tp * jonswap_tm01_over_tp(WIND_SEA_GAMMA)
    nan = np.where(sea, 0.0, np.nan)[None]
    parts_bg = [background_swell(swell, lat, lon, float(h)) for h in hours]
    bg_hs = np.stack([p[0] for p in parts_bg])
    bg_dir = np.stack([p[1] for p in parts_bg])
    bg_t = np.stack([p[2] for p in parts_bg])
    sw_parts = [(bg_hs, bg_dir, bg_t)]
    if track:
        src = _storm_sources(track, hours, ws_hs + nan, ws_tp, lat, lon)
        if src.size:
            dist, brg = distances_and_bearings(src[:, 1], src[:, 2], lat, lon)
            e, es, ec, eot = radiate(hours, src[:, 0], src[:, 3], src[:, 4], src[:, 5], src[:, 6],
                                     dist, brg, dt_s / S_PER_HOUR)
            st_hs = 4.0 * np.sqrt(e)
            st_dir = np.rad2deg(np.arctan2(es, ec)) % 360.0
            st_t = np.where(eot > 0, e / np.maximum(eot, 1e-12), 10.0)
            sw_parts.append((st_hs, st_dir, st_t))
    sw_hs, sw_dir, sw_tm = combine(sw_parts)
    tot_hs, tot_dir, tot_tm = combine([(ws_hs, ws_dir, ws_tm), (sw_hs, sw_dir, sw_tm)])
    cu0, cv0 = steady_currents(lat, lon)
    cu, cvv = with_wind_drift(cu0[None], cv0[None], u, v)
    return {
        cv.WIND_U: u, cv.WIND_V: v,
        cv.WAVE_HS: tot_hs + nan, cv.WAVE_DIR: tot_dir + nan, cv.WAVE_TM: tot_tm + nan,
        cv.WIND_WAVE_HS: ws_hs + nan, cv.WIND_WAVE_DIR: ws_dir + nan, cv.WIND_WAVE_TM: ws_tm + nan,
        cv.SWELL_HS: sw_hs + nan, cv.SWELL_DIR: sw_dir + nan, cv.SWELL_TM: sw_tm + nan,
        cv.CURRENT_U: cu + nan, cv.CURRENT_V: cvv + nan,
    }
