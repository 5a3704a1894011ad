"""Seeds for the GA: tracks (polylines + RPM per polyline leg) turned into heading/RPM genes.

`track_to_genes` marches the ship along each polyline stage by stage in the forecast: at every
node it steers (with current drift corrected) toward the polyline point one stage of speed
over ground ahead, using the RPM of the polyline leg it is on. The genes so reproduce the
track closely in the actual weather. Sources: great circle, `searoute` sea lanes, the seed
pool and a previous plan (shifted to the ship's current position and time).
"""

from __future__ import annotations

import itertools
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from shiproute_core.geodesy import direct, great_circle_points, inverse, unwrap_near

from ..geo.landmask import LandMask
from ..geo.sea_lanes import lane_between_points, sea_lane_between
from ..straits import is_gate_name
from .encoding import clip_genes, join_genes
from .environment import Environment
from .land_walk import LandWalk
from .legs import perf_arrays
from .problem import RouteProblem


@dataclass(frozen=True)
class TrackSeed:
    """A polyline from the departure to the arrival and the RPM on each of its legs."""

    source: str
    lon_deg: np.ndarray  # (k,)
    lat_deg: np.ndarray
    rpm: np.ndarray  # (k - 1,)


def _densify(seeds: list[TrackSeed], spacing_m: float
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Seeds resampled every ~`spacing_m` along their polylines, padded to one length:
    lon, lat, along-track distance (S, K) and RPM of the polyline leg at each point."""
    rows = []
    # timed versions of a seed share its polyline (the same arrays): resampled once
    resampled: dict[tuple[int, int], tuple] = {}
    for s in seeds:
        key = (id(s.lon_deg), id(s.lat_deg))
        if key not in resampled:
            lon = np.unwrap(s.lon_deg, period=360.0)
            _, seg = inverse(lon[:-1], s.lat_deg[:-1], lon[1:], s.lat_deg[1:])
            total = float(seg.sum())
            n = max(2, int(np.ceil(total / spacing_m)) + 1)
            resampled[key] = (*resample_track(lon, s.lat_deg, n),
                              np.concatenate([[0.0], np.cumsum(seg)]), np.linspace(0.0, total, n))
        plon, plat, cum, d = resampled[key]
        leg = np.clip(np.searchsorted(cum, d, side="right") - 1, 0, max(s.rpm.size - 1, 0))
        rows.append((plon, plat, d, s.rpm[leg] if s.rpm.size else np.zeros(d.size)))
    k = max(r[0].size for r in rows)
    out = [np.empty((len(rows), k)) for _ in range(4)]
    for i, r in enumerate(rows):
        m = r[0].size
        for a, v in zip(out, r, strict=True):
            a[i, :m] = v
            a[i, m:] = v[-1]
    return out[0], out[1], out[2], out[3]


StageSailor = Callable[[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray],
                      tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]


def stage_sailor(problem: RouteProblem, env: Environment, fast: Any = None) -> StageSailor:
    """(lon, lat, t, rpm, heading) -> (sog, cog, end lon, end lat) of one stage-long leg:
    compiled with a `FastEvaluator` (one call per stage for all seeds and candidates), else
    the environment's sea state, ship model and pyproj geodesic."""
    if fast is not None:
        return lambda lon, lat, t, rpm, hdg: fast.sail_stage(lon, lat, t, rpm, hdg,
                                                             problem.stage_s)

    def sail(lon, lat, t, rpm, hdg):
        n = np.size(lon)
        perf = perf_arrays(env.perform(rpm, hdg, env.sea_state(lon, lat, t)), (n,))
        sog, cog = perf["sog_m_s"], perf["cog_deg"]
        end_lon, end_lat = direct(lon, lat, cog, np.maximum(sog, 0.0) * problem.stage_s)
        return sog, cog, end_lon, end_lat

    return sail


def track_to_genes(problem: RouteProblem, env: Environment, seeds: list[TrackSeed],
                   land: LandMask | None = None, fan_deg: float = 60.0, fan_n: int = 13,
                   spacing_m: float = 10_000.0, fast: Any = None) -> np.ndarray:
    """Genes (len(seeds), 2n + 1) that follow each seed's polyline in the forecast.

    Per stage, candidate headings fan out around the course to the polyline point one stage
    of speed over ground ahead; the candidate whose leg stays off land and ends nearest that
    point wins (so 12-hour legs do not cut coasts where the polyline bends). Progress along
    the polyline is the nearest polyline point to the new node. `fast` (the GA's
    `FastEvaluator`) sails the candidates in compiled code.
    """
    lon, lat, _, rpm_at = _densify(seeds, spacing_m)
    rpm_at = sane_rpm(rpm_at, problem.limits.rpm_min, problem.limits.rpm_max)
    lon -= np.round((lon[:, :1] - problem.dep_lon_deg) / 360.0) * 360.0
    s_count, k = lon.shape
    rows = np.arange(s_count)
    offsets = np.linspace(-fan_deg, fan_deg, fan_n)
    offsets = offsets[np.argsort(np.abs(offsets), kind="stable")]
    scales = np.array([1.0, 0.8])  # shorter legs help to line up with straits
    offsets, scale = np.repeat(offsets, scales.size), np.tile(scales, offsets.size)
    c = offsets.size
    n = problem.n_stages
    headings = np.empty((s_count, n))
    rpm = np.empty((s_count, n + 1))
    node_lon = np.full(s_count, problem.dep_lon_deg)
    node_lat = np.full(s_count, problem.dep_lat_deg)
    t = np.full(s_count, problem.depart_s)
    idx = np.zeros(s_count, dtype=np.int64)
    sail = stage_sailor(problem, env, fast)
    # the GA's own land verdict when it has one (seeds it will not call land-crossing)
    land_hits = (None if land is None
                 else fast.segment_land_samples if fast is not None and fast.land is land
                 else LandWalk(problem, land).segments)
    for i in range(n):
        r = rpm_at[rows, idx]
        sog, _, _, _ = sail(node_lon, node_lat, t, r, np.zeros(s_count))
        step = np.maximum(sog, 0.1) * problem.stage_s
        tgt = np.minimum(idx + np.ceil(step / spacing_m).astype(np.int64), k - 1)
        course, _ = inverse(node_lon, node_lat, lon[rows, tgt], lat[rows, tgt])
        cand = (course[:, None] + offsets[None, :]) % 360.0  # (S, C)
        r_c = np.clip(np.repeat(r, c) * np.tile(scale, s_count), problem.limits.rpm_min,
                      problem.limits.rpm_max)
        sog_c, cog_c, end_lon, end_lat = sail(np.repeat(node_lon, c), np.repeat(node_lat, c),
                                              np.repeat(t, c), r_c, cand.ravel())
        dist = np.maximum(sog_c, 0.0) * problem.stage_s
        _, miss = inverse(end_lon, end_lat, np.repeat(lon[rows, tgt], c),
                          np.repeat(lat[rows, tgt], c))
        score = miss.reshape(s_count, c) + 2e6 * (1.0 - scale)[None, :]
        if land_hits is not None:
            s_lon, s_lat = np.repeat(node_lon, c), np.repeat(node_lat, c)
            if i == 0:  # same port clearance as the evaluator
                s_lon, s_lat = direct(s_lon, s_lat, cog_c,
                                      np.minimum(problem.port_clearance_m, dist))
            hits = land_hits(s_lon, s_lat, end_lon, end_lat)
            if i == n - 1:  # the final connection must reach the port too
                fin_lon = np.full(s_count * c, problem.arr_lon_deg)
                fin_lat = np.full(s_count * c, problem.arr_lat_deg)
                _, fd = inverse(end_lon, end_lat, fin_lon, fin_lat)
                f = np.clip(problem.port_clearance_m / np.maximum(fd, 1.0), 0.0, 1.0)
                hits = hits + land_hits(end_lon, end_lat, fin_lon - f * (fin_lon - end_lon),
                                        fin_lat - f * (fin_lat - end_lat))
            score = score + 1e9 * hits.reshape(s_count, c)
        if i > 0:  # the heading-change limit binds the genes: respect it here
            turn = (cand - headings[:, i - 1:i] + 180.0) % 360.0 - 180.0
            score = score + 1e12 * (np.abs(turn) > problem.limits.max_heading_change_deg)
        best = np.argmin(score, axis=1)
        pick = rows * c + best
        headings[:, i] = cand[rows, best]
        rpm[:, i] = r_c[pick]
        node_lon, node_lat = end_lon[pick], end_lat[pick]
        t = t + problem.stage_s
        # progress: nearest polyline point at or after the current one
        d2 = ((lon - node_lon[:, None]) * np.cos(np.radians(node_lat[:, None]))) ** 2 + (
            lat - node_lat[:, None]) ** 2
        d2 = np.where(np.arange(k)[None, :] >= idx[:, None], d2, np.inf)
        idx = np.argmin(d2, axis=1)
    rpm[:, n] = rpm_at[rows, idx]
    return clip_genes(problem, join_genes(headings, rpm))


def great_circle_track(problem: RouteProblem, n_points: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """Geodesic from departure to arrival as a polyline (default: one point per stage)."""
    n_points = n_points or problem.n_stages + 2
    return great_circle_points(problem.dep_lon_deg, problem.dep_lat_deg, problem.arr_lon_deg,
                               problem.arr_lat_deg, n_points)


def sea_lane_track(problem: RouteProblem, max_points: int = 0,
                   via: tuple[float, float] | None = None
                   ) -> tuple[np.ndarray, np.ndarray] | None:
    """Shortest sea-lane polyline from `searoute` (None if it finds no route).

    searoute snaps the end points to its network; the stops are put at the ends, and at a
    gate (open water on the lane, between nodes that may lie far off) the lane is first cut
    at its point nearest the gate (`lane_between_points`): a node past the gate would take
    the track over the shoal or strait the gate leads to and back. Long polylines are
    resampled to `max_points` (default two per stage)."""
    stops = [(problem.dep_lon_deg, problem.dep_lat_deg), (problem.arr_lon_deg, problem.arr_lat_deg)]
    if via is not None:
        stops.insert(1, (float(via[0]), float(via[1])))
    parts = []
    last = len(stops) - 2
    for i, (a, b) in enumerate(itertools.pairwise(stops)):
        part = sea_lane_between(a[0], a[1], b[0], b[1])
        if part is None:
            return None
        cut_a = i == 0 and is_gate_name(problem.dep_name)
        cut_b = i == last and is_gate_name(problem.arr_name)
        if cut_a or cut_b:
            start = a if cut_a else (float(part[0, 0]), float(part[0, 1]))
            end = b if cut_b else (float(part[-1, 0]), float(part[-1, 1]))
            part = lane_between_points(part, start[0], start[1], end[0], end[1])
        parts.append(part)
    coords = np.concatenate(parts, axis=0)
    if coords.shape[0] < 2:
        return None
    lon = np.unwrap(coords[:, 0], period=360.0)
    lon = unwrap_near(lon[0], problem.dep_lon_deg) + (lon - lon[0])
    lon = np.concatenate([[problem.dep_lon_deg], lon, [problem.arr_lon_deg]])
    lat = np.concatenate([[problem.dep_lat_deg], coords[:, 1], [problem.arr_lat_deg]])
    lon[-1] = unwrap_near(problem.arr_lon_deg, lon[-2])
    keep = np.concatenate([[True], np.hypot(np.diff(lon), np.diff(lat)) > 1e-4])
    lon, lat = lon[keep], lat[keep]
    max_points = max_points or 2 * problem.n_stages + 2
    if lon.size > max_points:
        lon, lat = resample_track(lon, lat, max_points)
    return lon, lat


def resample_track(lon: np.ndarray, lat: np.ndarray, n_points: int
                   ) -> tuple[np.ndarray, np.ndarray]:
    """`n_points` points equally spaced along a polyline (geodesic legs), ends kept."""
    az, seg = inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])
    cum = np.concatenate([[0.0], np.cumsum(seg)])
    d = np.linspace(0.0, cum[-1], n_points)
    j = np.clip(np.searchsorted(cum, d, side="right") - 1, 0, lon.size - 2)
    plon, plat = direct(lon[j], lat[j], az[j], d - cum[j])
    plon[0], plat[0], plon[-1], plat[-1] = lon[0], lat[0], lon[-1], lat[-1]
    return np.unwrap(plon, period=360.0), plat


def via_track(lon: np.ndarray, lat: np.ndarray, via_lon: float, via_lat: float,
              keep: float = 0.12) -> tuple[np.ndarray, np.ndarray]:
    """A polyline's first and last `keep` fraction (port approaches, straits) joined to a
    point (`via_lon`, `via_lat`) by great circles."""
    lon = np.unwrap(np.asarray(lon, dtype=float), period=360.0)
    _, seg = inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])
    s = np.concatenate([[0.0], np.cumsum(seg)]) / max(seg.sum(), 1.0)
    a = int(np.searchsorted(s, keep))
    b = int(np.searchsorted(s, 1.0 - keep))
    a, b = max(a, 0), min(max(b, a + 1), lon.size - 1)
    v_lon = float(unwrap_near(via_lon, lon[a]))
    l1, t1 = great_circle_points(lon[a], lat[a], v_lon, via_lat, 8)
    l2, t2 = great_circle_points(v_lon, via_lat, lon[b], lat[b], 8)
    out_lon = np.concatenate([lon[: a + 1], l1[1:], l2[1:], lon[b + 1:]])
    out_lat = np.concatenate([lat[: a + 1], t1[1:], t2[1:], lat[b + 1:]])
    return np.unwrap(out_lon, period=360.0), out_lat


def sane_rpm(rpm: np.ndarray, rpm_min: float, rpm_max: float) -> np.ndarray:
    """RPMs usable as seed values: non-finite entries take the nearest finite value along
    the last axis (mid-range if none), everything clipped into the engine range.

    A previous plan (or pool entry) can carry NaN RPMs, e.g. on a waypoint that ends a
    part of the plan; fed to the ship model they abort the whole re-plan."""
    r = np.array(rpm, dtype=float, copy=True)
    rows = r.reshape(-1, r.shape[-1]) if r.ndim else r.reshape(1, 1)
    for row in rows:
        ok = np.isfinite(row)
        if not ok.any():
            row[:] = 0.5 * (rpm_min + rpm_max)
        elif not ok.all():
            idx = np.flatnonzero(ok)
            near = idx[np.clip(np.searchsorted(idx, np.arange(row.size)), 0, idx.size - 1)]
            prev = idx[np.clip(np.searchsorted(idx, np.arange(row.size)) - 1, 0, idx.size - 1)]
            pick = np.where(np.abs(prev - np.arange(row.size)) <= np.abs(
                near - np.arange(row.size)), prev, near)
            row[~ok] = row[pick[~ok]]
    return np.clip(rows.reshape(r.shape), rpm_min, rpm_max)


def shift_track(lon: np.ndarray, lat: np.ndarray, time_s: np.ndarray, rpm: np.ndarray,
                now_lon: float, now_lat: float, now_s: float) -> TrackSeed | None:
    """The remainder of a previous plan after `now_s`, starting at the ship's position."""
    later = np.flatnonzero(np.asarray(time_s) > now_s)
    if later.size == 0:
        return None
    first = int(later[0])
    r = np.asarray(rpm, dtype=float)
    out_lon = np.concatenate([[now_lon], unwrap_near(np.asarray(lon)[first:], now_lon)])
    out_lat = np.concatenate([[now_lat], np.asarray(lat)[first:]])
    out_rpm = r[max(first - 1, 0):][: out_lon.size - 1]
    if out_rpm.size < out_lon.size - 1:
        out_rpm = np.concatenate([out_rpm, np.full(out_lon.size - 1 - out_rpm.size, r[-1])])
    return TrackSeed("previous_plan", np.unwrap(out_lon, period=360.0), out_lat, out_rpm)

