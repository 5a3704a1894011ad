"""Fast population evaluator for the GA: the same route model as `generate.evaluate_genes`
with the per-call overheads removed.

Per stage one call of the weather package's trilinear kernel (whole population), one
compiled call that turns the channels into sea states and runs the ship model's kernel, and
one compiled geodesic step (RK4 on the WGS 84 geodesic ODE instead of pyproj). Land: a
coarse (0.5 deg, dilated) raster filters out open-ocean segments; the rest go through the
same `LandMask.segment_land_samples` as the exact evaluator. Agreement with the exact
evaluator is tested; the planner re-evaluates its final choice exactly.
"""

from __future__ import annotations

import numba
import numpy as np

from ..geo.landmask import LandMask
from . import _fast_kernels as fk
from .encoding import split_genes
from .environment import PERF_FIELDS, Environment
from .evaluation import RouteEvaluation, clear_ports, finish
from .legs import MIN_SOG_M_S
from .problem import RouteProblem

# out_f rows / out_b rows of ship.fast_kernel.evaluate_kernel -> PERF_FIELDS
_F_ROWS = {"stw_m_s": 0, "sog_m_s": 1, "cog_deg": 2, "brake_power_kw": 3, "fuel_t_per_h": 4,
           "engine_load": 5, "hs_m": 6, "wind_speed_m_s": 7, "p_slamming": 8,
           "p_deck_wetness": 9, "p_propeller_emergence": 10}
_B_ROWS = {"engine_limit_exceeded": 0, "surf_riding": 1, "parametric_roll": 2,
           "synchronous_roll": 3, "high_wave_group": 4}
COARSE_FACTOR = 10  # 0.05 deg raster -> 0.5 deg near-land filter
LAND_QUANTUM_DEG = 0.002  # coastal samples tested at the centre of their ~200 m cell
_COARSE: dict[int, tuple[np.ndarray, np.ndarray]] = {}


class FastEvaluator:
    """Evaluate gene populations of one problem; build with `fast_evaluator` (None when the
    environment is not the tabulated ship model with a `ForecastSampler` or calm water)."""

    def __init__(self, problem: RouteProblem, env: Environment, land: LandMask | None) -> None:
        from shiproute_weather._interp_kernel import trilinear

        self.problem, self.env, self.land = problem, env, land
        self._trilinear = trilinear
        m = env.model
        self._ship = (m._par, *m._tables)
        self._limits = m._limits
        self._rpm_lo, self._rpm_hi = float(m._limits[0, 0]), float(m._limits[0, 1])
        self._wx = None
        if env.sampler is not None:
            from shiproute_weather.sampler_arrays import sampler_arrays

            a = sampler_arrays(env.sampler)
            self._wx = a
            self._chan = np.array([a.channels.get(v, -1) for v in fk.SEA_VARIABLES],
                                  dtype=np.int64)
            self._isdir = np.array([v in a.directions for v in fk.SEA_VARIABLES])
        self._coarse = None
        if land is not None:
            key = id(land)
            self._coarse_deg = land.cell_deg * COARSE_FACTOR
            if key not in _COARSE:
                coarse = fk.coarse_land_raster(np.asarray(land.raster), COARSE_FACTOR)
                _COARSE[key] = (coarse, fk.clear_distance_deg(coarse, self._coarse_deg))
            self._coarse, self._clear = _COARSE[key]

    def _stage(self, lon, lat, t, rpm, hdg) -> tuple[np.ndarray, np.ndarray]:
        """Ship model outputs (11, P) and flags (5, P) at the points for rpm/heading."""
        pop = lon.size
        sea = np.empty((10, pop))
        if self._wx is None:
            sea[:] = 0.0
            sea[4] = sea[7] = 8.0
        else:
            a = self._wx
            wx = np.empty((a.data.shape[3], pop))
            self._trilinear(a.data, a.times_s, a.lat0_deg, a.dlat_deg, a.lon0_deg, a.dlon_deg,
                            a.periodic, lon, lat, t, wx)
            fk.fill_sea(wx, self._chan, self._isdir, sea, self._limits)
        return self._perform(rpm, hdg, sea), sea

    def _perform(self, rpm, hdg, sea) -> tuple[np.ndarray, np.ndarray]:
        out_f = np.empty((11, rpm.size))
        out_b = np.empty((5, rpm.size), dtype=np.bool_)
        r = np.clip(rpm, self._rpm_lo, self._rpm_hi)
        fk.perform(r, np.ascontiguousarray(hdg % 360.0), sea, *self._ship, out_f, out_b)
        return out_f, out_b

    def evaluate(self, x: np.ndarray) -> RouteEvaluation:
        """Generate and evaluate routes from genes `x` (pop, 2n + 1).

        Runs on one thread: for a few hundred points per stage, waking numba's workers
        costs more than the work (and far more on a busy machine)."""
        prev = numba.get_num_threads()
        numba.set_num_threads(1)
        try:
            return self._evaluate(x)
        finally:
            numba.set_num_threads(prev)

    def _evaluate(self, x: np.ndarray) -> RouteEvaluation:
        p = self.problem
        headings, rpm = split_genes(p, x)
        pop, n = headings.shape
        m = n + 1
        lon = np.empty((pop, m + 1))
        lat = np.empty((pop, m + 1))
        t = np.empty((pop, m + 1))
        lon[:, 0], lat[:, 0], t[:, 0] = p.dep_lon_deg, p.dep_lat_deg, p.depart_s
        out_f = np.empty((11, pop, m))
        out_b = np.empty((5, pop, m), dtype=np.bool_)
        nl, nt = np.empty(pop), np.empty(pop)
        for i in range(n):
            lo_i, la_i, t_i = (np.ascontiguousarray(a[:, i]) for a in (lon, lat, t))
            (f, b), _ = self._stage(lo_i, la_i, t_i, np.ascontiguousarray(rpm[:, i]),
                                    headings[:, i])
            out_f[:, :, i], out_b[:, :, i] = f, b
            fk.direct_many(lo_i, la_i, f[2], np.maximum(f[1], 0.0) * p.stage_s, nl, nt)
            lon[:, i + 1], lat[:, i + 1] = nl, nt
            t[:, i + 1] = t_i + p.stage_s
        # final connection: steer so that the course over ground points at the port
        lo_n, la_n, t_n = (np.ascontiguousarray(a[:, n]) for a in (lon, lat, t))
        arr_lon, arr_lat = np.full(pop, p.arr_lon_deg), np.full(pop, p.arr_lat_deg)
        course, dist_n = np.empty(pop), np.empty(pop)
        fk.inverse_many(lo_n, la_n, arr_lon, arr_lat, course, dist_n)
        rpm_n = np.ascontiguousarray(rpm[:, n])
        (f, b), sea = self._stage(lo_n, la_n, t_n, rpm_n, course)
        drift = (f[2] - course + 180.0) % 360.0 - 180.0
        heading_n = course.copy()
        if np.any(np.abs(drift) > 1e-6):
            heading_n = (course - drift) % 360.0
            f, b = self._perform(rpm_n, heading_n, sea)
        out_f[:, :, n], out_b[:, :, n] = f, b
        along = f[1] * np.cos(np.radians(f[2] - course))
        dur_n = np.where(dist_n > 0.0, dist_n / np.maximum(along, MIN_SOG_M_S), 0.0)
        lon[:, m], lat[:, m] = p.arr_lon_deg, p.arr_lat_deg
        t[:, m] = t_n + dur_n
        legs = {k: out_f[r] for k, r in _F_ROWS.items()}
        legs.update({k: out_b[r] for k, r in _B_ROWS.items()})
        legs = {k: legs[k] for k in PERF_FIELDS}
        duration = np.full((pop, m), p.stage_s)
        duration[:, n] = dur_n
        distance = np.empty((pop, m))
        distance[:, :n] = np.maximum(legs["sog_m_s"][:, :n], 0.0) * p.stage_s
        distance[:, n] = dist_n
        legs["heading_deg"] = np.concatenate([headings, heading_n[:, None]], axis=1)
        legs["rpm"] = rpm
        legs["distance_m"] = distance
        legs["duration_s"] = duration
        legs["fuel_t"] = legs["fuel_t_per_h"] * duration / 3600.0
        legs["turn_deg"] = np.zeros((pop, m))
        return finish(p, self.land, lon, lat, t, legs, self._land_samples(lon, lat, distance))

    def _land_samples(self, lon, lat, distance) -> np.ndarray | None:
        """Land samples per leg: coarse filter, then the exact evaluator's segment test."""
        if self.land is None:
            return None
        ends = [np.ascontiguousarray(e).ravel()
                for e in clear_ports(self.problem, lon, lat, distance)]
        near = np.empty(ends[0].size, dtype=np.bool_)
        fk.near_land(*ends, self._coarse, self._clear, self._coarse_deg, 0.4 * self._coarse_deg,
                     near)
        out = np.zeros(ends[0].size, dtype=np.int64)
        idx = np.flatnonzero(near)
        if idx.size:
            out[idx] = self.land.segment_land_samples(
                *(e[idx] for e in ends), self.problem.land_spacing_deg,
                quantum_deg=LAND_QUANTUM_DEG)
        return out.reshape(distance.shape)


def fast_evaluator(problem: RouteProblem, env: Environment,
                   land: LandMask | None) -> FastEvaluator | None:
    """A `FastEvaluator` if the environment supports it, else None (use `evaluate_genes`)."""
    from ..ship.fast import FastModel

    if not isinstance(env.model, FastModel):
        return None
    if env.sampler is not None:
        from shiproute_weather.sampling import ForecastSampler

        if not isinstance(env.sampler, ForecastSampler):
            return None
    return FastEvaluator(problem, env, land)
