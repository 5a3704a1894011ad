"""What a route-finding method gets and gives: the leg's context, progress and result, and the
constant-RPM baseline every method is judged against (great circle, else the sea lane)."""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from shiproute_core.geodesy import inverse

from .ga.loop import GAConfig
from .geo.landmask import LandMask
from .route.environment import Environment
from .route.evaluation import RouteEvaluation, clear_ports
from .route.land_walk import LandWalk
from .route.problem import RouteProblem
from .route.rta import constant_rpm_for_rta
from .route.seed_repair import repaired_seed_track
from .route.seeding import TrackSeed, great_circle_track, sea_lane_track


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
    n_offset_seeds: int = 4  # sea lanes via bent points per position (0 = none)
    offset_span_deg: float = 12.0
    stall_generations: int = 0  # 0 = no stall termination
    baseline: Baseline | None = None  # computed on demand when None
    gene_seeds: list[tuple[str, np.ndarray]] = field(default_factory=list)  # ready genes
    max_evaluations: int = 0  # stop after this many route evaluations (0 = no limit)
    n_islands: int = 3  # seed GA: seed groups searched apart (by side of the great circle)
    island_share: float = 0.5  # share of the search (time, generations or evaluations)
    # before the islands merge


@dataclass(frozen=True)
class MethodResult:
    """Chosen route and search statistics."""

    evaluation: RouteEvaluation  # one row
    seed_source: str
    generations: int = 0
    evaluations: int = 0
    genes: np.ndarray | None = None  # heading/RPM genes of the route, when the method has them
    notes: tuple[str, ...] = ()  # what the plan says about this leg's search (its warnings)


@dataclass(frozen=True)
class Baseline:
    """Constant-RPM route meeting the RTA on the great circle or the sea lane."""

    name: str
    lon_deg: np.ndarray
    lat_deg: np.ndarray
    rpm: float
    evaluation: RouteEvaluation


def compute_baseline(problem: RouteProblem, env: Environment, land: LandMask) -> Baseline:
    """Great circle if it stays off land, else the sea lane; slowest RPM meeting the RTA."""
    name, lon, lat = baseline_track(problem, land)
    rpm, ev = constant_rpm_for_rta(problem, env, land, lon, lat)
    return Baseline(name, lon, lat, rpm, ev)


MethodFn = Callable[[MethodContext], MethodResult]


def baseline_track(problem: RouteProblem, land: LandMask) -> tuple[str, np.ndarray, np.ndarray]:
    """Great circle if it stays off land, else the `searoute` sea lane (else the great circle)."""
    lon, lat = great_circle_track(problem)
    _, dist = inverse(lon[:-1], lat[:-1], lon[1:], lat[1:])
    ends = clear_ports(problem, lon[None, :], lat[None, :], dist[None, :])
    hits = LandWalk(problem, land).segments(*ends)
    if hits.sum() == 0:
        return "great_circle", lon, lat
    lane = sea_lane_track(problem)
    if lane is None:
        return "great_circle", lon, lat
    # the lane's own geometry cuts headlands and narrow passages: detoured at full
    # resolution, so the baseline and the seeds made from it start off land
    lane_lon, lane_lat, _ = repaired_seed_track(problem, lane[0], lane[1])
    return "sea_lane", lane_lon, lane_lat


