"""Registry of planning methods: name -> function(MethodContext) -> MethodResult.

Every method plans one leg (`RouteProblem`) with the shared evaluator and returns the chosen
route as a single-row `RouteEvaluation`. Baseline methods (isochrone, A*, 3DDP, pymoo)
register themselves with `register_method`.
"""

from __future__ import annotations

import contextlib
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from .errors import UnknownMethodError
from .ga.loop import GAConfig, SeedGA
from .ga.seeds import (
    TrackSeed,
    great_circle_track,
    sea_lane_track,
    track_to_genes,
)
from .geo.geodesy import inverse
from .geo.landmask import LandMask
from .route.encoding import gene_bounds
from .route.environment import Environment
from .route.evaluation import RouteEvaluation
from .route.generate import evaluate_genes
from .route.problem import RouteProblem
from .route.rta import constant_rpm_for_rta


@dataclass(frozen=True)
class Progress:
    """Progress of a running plan (for CLI output and ROS action feedback)."""

    leg: int
    generation: int
    evaluations: int
    best_objective: float  # NaN while nothing feasible is known
    best_violation: float
    elapsed_s: float


@dataclass
class MethodContext:
    """Everything a method needs for one leg."""

    problem: RouteProblem
    env: Environment
    land: LandMask
    rng: np.random.Generator
    budget_s: float
    seeds: list[TrackSeed] = field(default_factory=list)
    progress: Callable[[Progress], None] | None = None
    cancelled: Callable[[], bool] = lambda: False
    leg_index: int = 0
    t_start: float = field(default_factory=time.perf_counter)
    ga_config: GAConfig | None = None
    max_generations: int = 100_000
    n_offset_seeds: int = 6  # bent copies of the sea-lane/great-circle seed (0 = none)
    offset_span_deg: float = 12.0
    stall_generations: int = 0  # 0 = no stall termination


@dataclass(frozen=True)
class MethodResult:
    """Chosen route and search statistics."""

    evaluation: RouteEvaluation  # one row
    seed_source: str
    generations: int = 0
    evaluations: int = 0


MethodFn = Callable[[MethodContext], MethodResult]
_METHODS: dict[str, MethodFn] = {}


def register_method(name: str, fn: MethodFn) -> None:
    """Add or replace a planning method."""
    _METHODS[name] = fn


def get_method(name: str) -> MethodFn:
    """The method registered as `name`."""
    _load_plugins()
    try:
        return _METHODS[name]
    except KeyError:
        raise UnknownMethodError(
            f"planning method {name!r} is unknown; available: {', '.join(sorted(_METHODS))}"
        ) from None


def method_names() -> list[str]:
    """Registered method names."""
    _load_plugins()
    return sorted(_METHODS)


def _load_plugins() -> None:
    """Import optional method modules that register themselves (baselines package)."""
    with contextlib.suppress(ImportError):
        from . import baselines  # noqa: F401


def baseline_track(problem: RouteProblem, land: LandMask) -> tuple[str, np.ndarray, np.ndarray]:
    """Great circle if it stays off land, else the `searoute` sea lane (else the great circle)."""
    lon, lat = great_circle_track(problem)
    hits = land.segment_land_samples(lon[:-1], lat[:-1], lon[1:], lat[1:])
    if hits.sum() == 0:
        return "great_circle", lon, lat
    lane = sea_lane_track(problem)
    if lane is None:
        return "great_circle", lon, lat
    return "sea_lane", lane[0], lane[1]


def great_circle_method(ctx: MethodContext) -> MethodResult:
    """Constant RPM meeting the RTA on the great circle (sea lane if the circle hits land)."""
    name, lon, lat = baseline_track(ctx.problem, ctx.land)
    _, ev = constant_rpm_for_rta(ctx.problem, ctx.env, ctx.land, lon, lat)
    return MethodResult(ev, name, 0, 1)


def seed_ga_method(ctx: MethodContext) -> MethodResult:
    """Seed GA: seeds (pool, previous plan, sea lane, great circle) + GA within the budget."""
    p, env = ctx.problem, ctx.env
    seeds = list(ctx.seeds)
    base = None
    for name, lon, lat in _default_tracks(p, ctx.land, with_lane=not seeds):
        rpm, ev = constant_rpm_for_rta(p, env, None, lon, lat, n_try=12, rounds=2)
        seeds.append(TrackSeed(name, lon, lat, np.full(lon.size - 1, rpm)))
        base = (name, lon, lat, rpm, float(ev.distance_m[0]))
    if base is not None and ctx.n_offset_seeds:
        _, _, _, rpm, dist = base
        mid_lon, mid_lat = great_circle_track(p, 3)
        spread = np.linspace(-ctx.offset_span_deg, ctx.offset_span_deg, ctx.n_offset_seeds + 1)
        for d in spread[spread != 0.0]:
            mlat = float(np.clip(mid_lat[1] + d, -p.limits.lat_bound_deg, p.limits.lat_bound_deg))
            lane = sea_lane_track(p, via=(float(mid_lon[1]), mlat))
            if lane is None:
                continue
            olon, olat = lane
            length = float(np.sum(inverse(olon[:-1], olat[:-1], olon[1:], olat[1:])[1]))
            r = float(np.clip(rpm * length / dist, p.limits.rpm_min, p.limits.rpm_max))
            seeds.append(TrackSeed("searoute_via", olon, olat, np.full(olon.size - 1, r)))
    x_seed = track_to_genes(p, env, seeds, ctx.land)
    sources = [s.source for s in seeds]
    lo, hi = gene_bounds(p)
    cfg = ctx.ga_config or GAConfig()
    ga = SeedGA(lo, hi, p.n_stages, cfg, ctx.rng, x_seed)
    best_src = "none"
    while True:
        x = ga.ask()
        ev = evaluate_genes(p, env, ctx.land, x)
        ga.tell(x, ev.violation, ev.objective)
        if ga.generation == 0:
            order = np.lexsort((ev.objective[: len(sources)], ev.violation[: len(sources)] > 0,
                                ev.violation[: len(sources)]))
            best_src = sources[int(order[0])] if sources else "none"
        _, v, f = ga.best
        elapsed = time.perf_counter() - ctx.t_start
        if ctx.progress is not None:
            ctx.progress(Progress(ctx.leg_index, ga.generation, ga.evaluations,
                                  f if v <= 0 else float("nan"), v, elapsed))
        if (elapsed >= ctx.budget_s or ga.generation >= ctx.max_generations or ctx.cancelled()
                or (ctx.stall_generations and ga.stalled(ctx.stall_generations))):
            break
    best_x, _, _ = ga.best
    final = evaluate_genes(p, env, ctx.land, best_x[None, :])
    return MethodResult(final, best_src, ga.generation, ga.evaluations)


def _default_tracks(p: RouteProblem, land: LandMask, with_lane: bool = True):
    """Great-circle and sea-lane polylines as seed tracks."""
    lon, lat = great_circle_track(p)
    yield "great_circle", lon, lat
    if with_lane:
        lane = sea_lane_track(p)
        if lane is not None:
            yield "searoute", lane[0], lane[1]


register_method("seed_ga", seed_ga_method)
register_method("great_circle", great_circle_method)
