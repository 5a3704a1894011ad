"""Fast population evaluator for the GA: the same route model as `generate.evaluate_genes`
with the per-call overheads removed.

One compiled call (`_route_kernel.generate_routes`) generates a whole population: per stage
the weather package's trilinear kernel, the sea state, the ship model's kernel and a geodesic
step (RK4 on the WGS 84 geodesic ODE instead of pyproj). Land: the finest coastline installed
with the problem's clearance rule (`route.clearance`), walked on the signed distance to the
coast (`_land_walk.clearance_walk`: coarse clear distances, level 0, level-1 tiles built as
the walk meets them); a leg closer to land than the rule allows counts as on land. Agreement
with the exact evaluator is tested; the planner re-evaluates its final choice exactly.
Constraints and totals:
`fast_finish` (compiled, the same bits as `evaluation.finish`).
"""

from __future__ import annotations

import numpy as np

from ..chunks import in_chunks
from ..geo.landmask import LandMask
from . import _fast_kernels as fk
from . import _finish_kernel as kf
from . import _route_kernel as rk
from . import member_kernel as mk
from .encoding import split_genes
from .environment import PERF_FIELDS, Environment
from .evaluation import RouteEvaluation
from .fast_finish import Ends, Work, finish_fast, leg_cuts
from .land_walk import COARSE_FACTOR, LandWalk, coarse_land  # noqa: F401 (re-exported)
from .problem import RouteProblem

# out_f rows / out_b rows of ship.fast_kernel.evaluate_kernel -> PERF_FIELDS
_F_ROWS = {"stw_m_s": 0, "sog_m_s": 1, "cog_deg": 2, "brake_power_kw": 3, "fuel_t_per_h": 4,
           "engine_load": 5, "hs_m": 6, "wind_speed_m_s": 7, "p_slamming": 8,
           "p_deck_wetness": 9, "p_propeller_emergence": 10}
_B_ROWS = {"engine_limit_exceeded": 0, "surf_riding": 1, "parametric_roll": 2,
           "synchronous_roll": 3, "high_wave_group": 4}


class FastEvaluator:
    """Evaluate gene populations of one problem; build with `fast_evaluator` (None when the
    environment is not the tabulated ship model with a `ForecastSampler` or calm water)."""

    def __init__(self, problem: RouteProblem, env: Environment, land: LandMask | None) -> None:
        self.problem, self.env, self.land = problem, env, land
        from ..ship.fast import FastModel

        m = env.model
        assert isinstance(m, FastModel), "`fast_evaluator` builds one for the tabulated model only"
        par, tables, self._limits = m.kernel_arrays()
        self._ship = (par, *tables)
        self._rpm_lo, self._rpm_hi = float(self._limits[0, 0]), float(self._limits[0, 1])
        if env.sampler is not None:
            from shiproute_weather.sampling.sampler import ForecastSampler
            from shiproute_weather.sampling.sampler_arrays import sampler_arrays

            assert isinstance(env.sampler, ForecastSampler), "built for a ForecastSampler only"
            a = sampler_arrays(env.sampler)
            chan = np.array([a.channels.get(v, -1) for v in fk.SEA_VARIABLES], dtype=np.int64)
            isdir = np.array([v in a.directions for v in fk.SEA_VARIABLES])
            self._weather = (True, a.data, a.times_s, a.lat0_deg, a.dlat_deg, a.lon0_deg,
                             a.dlon_deg, bool(a.periodic), chan, isdir)
        else:  # calm water: the kernel skips sampling
            self._weather = (False, np.zeros((1, 1, 1, 1)), np.zeros(1), 0.0, 1.0, 0.0, 1.0,
                             False, np.full(len(fk.SEA_VARIABLES), -1, dtype=np.int64),
                             np.zeros(len(fk.SEA_VARIABLES), dtype=np.bool_))
        self._members = None
        if env.sampler is not None and getattr(env.sampler, "members", None) is not None:
            self._members = env.sampler.members
        self._walk = None if land is None else LandWalk(problem, land)  # the finest coastline

    def evaluate(self, x: np.ndarray) -> RouteEvaluation:
        """Generate and evaluate routes from genes `x` (pop, 2n + 1): each thread's rows
        generated and their leg arrays and port-cut leg ends assembled in one piece of
        work (`_finish_kernel.assemble_and_cut`: one compiled call), then land, depth and
        constraints (`fast_finish.finish_fast`)."""
        p = self.problem
        headings, rpm = split_genes(p, x)
        pop, n = headings.shape
        m = n + 1
        lon, lat, t = np.empty((pop, m + 1)), np.empty((pop, m + 1)), np.empty((pop, m + 1))
        out_f = np.empty((11, pop, m))
        out_b = np.empty((5, pop, m), dtype=np.bool_)
        heading_n, dist_n, dur_n = np.empty(pop), np.empty(pop), np.empty(pop)
        headings, rpm = np.ascontiguousarray(headings), np.ascontiguousarray(rpm)
        duration, distance, heading, fuel = (np.empty((pop, m)) for _ in range(4))
        cuts = leg_cuts(p)
        ends = np.empty((4 * len(cuts), pop, m))  # lon0, lat0, lon1, lat1 per cut
        cuts_m = np.array(cuts)

        def generate(a: int, b: int) -> None:
            rk.generate_routes(headings[a:b], rpm[a:b], p.dep_lon_deg, p.dep_lat_deg,
                               p.depart_s, p.stage_s, p.arr_lon_deg, p.arr_lat_deg,
                               self._rpm_lo, self._rpm_hi, *self._weather, self._limits,
                               *self._ship, lon[a:b], lat[a:b], t[a:b], out_f[:, a:b],
                               out_b[:, a:b], heading_n[a:b], dist_n[a:b], dur_n[a:b])
            kf.assemble_and_cut(out_f[_F_ROWS["sog_m_s"], a:b],
                                out_f[_F_ROWS["fuel_t_per_h"], a:b], headings[a:b],
                                heading_n[a:b], dist_n[a:b], dur_n[a:b], p.stage_s, lon[a:b],
                                lat[a:b], p.dep_lon_deg, p.dep_lat_deg, p.arr_lon_deg,
                                p.arr_lat_deg, cuts_m, duration[a:b], distance[a:b],
                                heading[a:b], fuel[a:b], ends[:, a:b])

        in_chunks(pop, generate)
        legs = self._perf_legs(out_f, out_b)
        legs.update(heading_deg=heading, rpm=rpm, distance_m=distance, duration_s=duration,
                    fuel_t=fuel, turn_deg=np.zeros((pop, m)))
        scan = None if self.land is None else self._land_verdicts
        cut_ends = {cut: (ends[4 * c], ends[4 * c + 1], ends[4 * c + 2], ends[4 * c + 3])
                    for c, cut in enumerate(cuts)}
        return finish_fast(p, lon, lat, t, legs, scan, cut_ends)

    @property
    def member_count(self) -> int:
        """Ensemble members of the forecast (1: one forecast)."""
        return 1 if self._members is None else self._members.count

    @property
    def member_weights(self) -> np.ndarray:
        """Weights of the ensemble members (sum 1)."""
        return np.ones(1) if self._members is None else self._members.weights

    def evaluate_members(self, x: np.ndarray) -> RouteEvaluation:
        """Genes `x` (pop, 2n + 1) sailed on every ensemble member in one compiled call
        (`member_kernel.generate_member_routes`): rows member-major, row k * pop + i is
        candidate i on member k; needs a forecast with members."""
        assert self._members is not None, "evaluate_members needs an ensemble forecast"
        p = self.problem
        headings, rpm = split_genes(p, x)
        pop, n = headings.shape
        m, mc = n + 1, self._members.count
        lon, lat, t = (np.empty((mc, pop, m + 1)) for _ in range(3))
        out_f = np.empty((11, mc, pop, m))
        out_b = np.empty((5, mc, pop, m), dtype=np.bool_)
        heading_n, dist_n, dur_n = (np.empty((mc, pop)) for _ in range(3))
        headings, rpm = np.ascontiguousarray(headings), np.ascontiguousarray(rpm)
        wx = (self._weather[0], self._members.kernel_data, *self._weather[2:])

        def generate(a: int, b: int) -> None:
            mk.generate_member_routes(
                headings[a:b], rpm[a:b], p.dep_lon_deg, p.dep_lat_deg, p.depart_s, p.stage_s,
                p.arr_lon_deg, p.arr_lat_deg, self._rpm_lo, self._rpm_hi, *wx, self._limits,
                *self._ship, lon[:, a:b], lat[:, a:b], t[:, a:b], out_f[:, :, a:b],
                out_b[:, :, a:b], heading_n[:, a:b], dist_n[:, a:b], dur_n[:, a:b])

        in_chunks(pop, generate)
        rows = mc * pop
        return self._finish(np.tile(headings, (mc, 1)), np.tile(rpm, (mc, 1)),
                            lon.reshape(rows, -1), lat.reshape(rows, -1), t.reshape(rows, -1),
                            out_f.reshape(11, rows, m), out_b.reshape(5, rows, m),
                            heading_n.reshape(-1), dist_n.reshape(-1), dur_n.reshape(-1))

    def _finish(self, headings, rpm, lon, lat, t, out_f, out_b, heading_n, dist_n,
                dur_n) -> RouteEvaluation:
        """Leg arrays, land samples and constraints of generated routes."""
        p = self.problem
        pop, n = headings.shape
        m = n + 1
        legs = self._perf_legs(out_f, out_b)
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
        scan = None if self.land is None else self._land_verdicts
        return finish_fast(p, lon, lat, t, legs, scan)

    @staticmethod
    def _perf_legs(out_f: np.ndarray, out_b: np.ndarray) -> dict[str, np.ndarray]:
        """The ship model's leg arrays (views of the kernel's output rows), PERF_FIELDS order."""
        legs = {k: out_f[r] for k, r in _F_ROWS.items()}
        legs.update({k: out_b[r] for k, r in _B_ROWS.items()})
        return {k: legs[k] for k in PERF_FIELDS}

    def sail_stage(self, lon: np.ndarray, lat: np.ndarray, t: np.ndarray, rpm: np.ndarray,
                   heading_deg: np.ndarray, duration_s: float
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Speed [m/s] and course [deg] over ground of one leg from each point (time `t`)
        at `rpm` and `heading_deg` for `duration_s`, and its end (lon, lat) [deg]."""
        lon_c, lat_c, t_c, rpm_c, heading_c = (
            np.ascontiguousarray(a, dtype=float) for a in (lon, lat, t, rpm, heading_deg))
        sog, cog, lon1, lat1 = (np.empty(lon_c.size) for _ in range(4))
        rk.sail_stage(lon_c, lat_c, t_c, rpm_c, heading_c, float(duration_s), *self._weather,
                      self._limits, *self._ship, sog, cog, lon1, lat1)
        return sog, cog, lon1, lat1

    def polyline_eta(self, lon: np.ndarray, lat: np.ndarray, rpm: np.ndarray) -> np.ndarray:
        """Arrival times [POSIX s] of the polyline (lon, lat) [deg] sailed from the problem's
        departure at each constant `rpm` (legs steered as `route.legs.sail_to` does)."""
        track_lon = np.ascontiguousarray(np.unwrap(np.asarray(lon, dtype=float), period=360.0))
        track_lat = np.ascontiguousarray(lat, dtype=float)
        eta = np.empty(np.size(rpm))
        rk.polyline_eta(track_lon, track_lat, np.ascontiguousarray(rpm, dtype=float).ravel(),
                        self.problem.depart_s, *self._weather, self._limits, *self._ship, eta)
        return eta

    def _land_verdicts(self, ends: Ends, alongside: Work | None = None) -> np.ndarray:
        """Violations per leg (ends (pop, m) with the ports cut off) from the compiled walk
        (`_land_walk.clearance_walk`); tiles it meets for the first time are built and their
        legs walked again. `alongside`: other work over the same legs, run with the first
        walk on the same threads."""
        return self.segment_land_samples(*ends, alongside=alongside).reshape(ends[0].shape)

    def segment_land_samples(self, lon0: np.ndarray, lat0: np.ndarray, lon1: np.ndarray,
                             lat1: np.ndarray, alongside: Work | None = None) -> np.ndarray:
        """The GA's verdict of great-circle segments (flattened): samples on land or closer
        to the coast than the problem's clearance rule allows (0 = clear; `land_walk`);
        needs a land mask. `alongside(a, b)`: work on segments a..b run in the first walk's
        threads (one fan-out for both)."""
        assert self._walk is not None, "FastEvaluator built without a land mask"
        return self._walk.segments(np.ravel(lon0), np.ravel(lat0), np.ravel(lon1),
                                   np.ravel(lat1), alongside=alongside)


def fast_evaluator(problem: RouteProblem, env: Environment,
                   land: LandMask | None) -> FastEvaluator | None:
    """A `FastEvaluator` if the environment supports it, else None (use `evaluate_genes`)."""
    from ..ship.fast import FastModel

    if not isinstance(env.model, FastModel):
        return None
    if env.sampler is not None:
        from shiproute_weather.sampling.sampler import ForecastSampler

        if not isinstance(env.sampler, ForecastSampler):
            return None
    return FastEvaluator(problem, env, land)
