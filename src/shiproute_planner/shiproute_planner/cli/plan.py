"""Plan a voyage: seed GA (or another method) -> summary, RTZ 1.2, GeoJSON, JSON and PNG."""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

from shiproute_planner.plan_setup import load_forecast

from ..errors import InvalidVoyageError, PlannerError
from ..method_context import Progress
from ..methods import method_names
from ..objectives import (
    DEFAULT_CHARTER_USD_PER_DAY,
    DEFAULT_FUEL_PRICE_USD_PER_T,
    PLAN_OBJECTIVES,
)
from ..plan_request import build_request, duration_s, run_request
from ..route.clearance import DEFAULT_CLEARANCE
from ..ship.fuel import CO2_FACTOR_T_PER_T
from .option_ranges import PLAN_OPTIONS, check_options, risk_option
from .warm_up import warm_up, warm_up_note


def parse_duration_s(text: str) -> float:
    """'13d', '36h', '90m', '3s' or plain seconds -> seconds."""
    try:
        return duration_s(text)
    except PlannerError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def build_parser() -> argparse.ArgumentParser:
    """Argument parser of `shiproute plan`."""
    ap = argparse.ArgumentParser(prog="shiproute plan", description=__doc__)
    ap.add_argument("--from", dest="origin", required=True, help="port name, UN/LOCODE or lat,lon")
    ap.add_argument("--to", dest="destination", required=True)
    ap.add_argument("--via", action="append", default=[],
                    metavar="PORT[@EARLIEST..LATEST][+BERTH_H]",
                    help="port call (repeatable): optional arrival window (ISO UTC times or "
                         "offsets after departure such as 3d; either end may be left out; "
                         "'@TIME' alone is a latest arrival) and berth time in hours; the "
                         "leg times are scheduled together for the least fuel")
    ap.add_argument("--depart", required=True, help="ISO 8601 UTC, e.g. 2026-03-03T18:00Z")
    ap.add_argument("--rta", required=True,
                    help="required time of arrival: ISO time or duration after departure (13d)")
    ap.add_argument("--ship", default="container_4600teu", help="bundled ship or YAML path")
    ap.add_argument("--model", default="",
                    help="ship model: physics (tabulated, the fast path), physics-direct, kwon, "
                         "profile:FILE.nc or learned:FILE.nc (default: the ship file's "
                         "performance_model entry, else physics)")
    ap.add_argument("--forecast", action="append", default=[],
                    help="forecast file (GRIB1/2, NetCDF) or bundled scenario; repeat to make "
                         "one cycle of several files (e.g. wind, waves, currents); omit for "
                         "calm water")
    ap.add_argument("--no-wave-estimate", action="store_true",
                    help="refuse a forecast with wind but no waves instead of estimating the "
                         "waves from the wind")
    ap.add_argument("--climatology", default=None,
                    help="monthly climatology file (GRIB/NetCDF, one valid time per month) "
                         "used beyond the forecast and its persistence instead of calm water")
    ap.add_argument("--persistence-hours", type=float, default=24.0,
                    help="hold the forecast's last fields this long beyond its last valid "
                         "time, then assume calm water (default 24)")
    ap.add_argument("--objective", choices=PLAN_OBJECTIVES, default="fuel",
                    help="fuel, distance, eta (earliest arrival), co2 (fuel x the fuel's IMO "
                         "carbon factor), cost (fuel price x fuel + charter rate x time), or "
                         "front: the time-fuel Pareto front (--front-points plans)")
    ap.add_argument("--front-points", type=int, default=9,
                    help="plans on the time-fuel front (objective front; default 9)")
    ap.add_argument("--loading", default="",
                    help="loading condition: a condition of the ship file (design, ballast) "
                         "or drafts fore,aft in metres (11.5,12.5); default: the file's")
    ap.add_argument("--fuel-type", default=None, choices=sorted(CO2_FACTOR_T_PER_T),
                    help="fuel burned, for co2/cost (default: the ship file's fuel_type, "
                         "else HFO)")
    ap.add_argument("--fuel-price", type=float, default=None, metavar="USD_PER_T",
                    help=f"fuel price for the cost objective (default: ship file economics, "
                         f"else {DEFAULT_FUEL_PRICE_USD_PER_T:.0f} USD/t)")
    ap.add_argument("--charter-rate", type=float, default=None, metavar="USD_PER_DAY",
                    help=f"time-charter rate for the cost objective (default: ship file "
                         f"economics, else {DEFAULT_CHARTER_USD_PER_DAY:.0f} USD/day)")
    ap.add_argument("--risk", default=None, metavar="MEASURE",
                    help="plan on every ensemble member minimising mean, cvar:ALPHA (e.g. "
                         "cvar:0.9) or worst of the objective (default: the members' mean "
                         "forecast)")
    ap.add_argument("--p-hs-max", type=float, default=None, metavar="P",
                    help="with --risk: largest accepted probability of meeting Hs above the "
                         "ship's limit (0..1, default 0)")
    ap.add_argument("--p-late-max", type=float, default=None, metavar="P",
                    help="with --risk: largest accepted probability of arriving late even "
                         "at MCR after heave-to in seas above the limit (0..1, default 0)")
    ap.add_argument("--method", default="seed_ga", help="planning method (see --list-methods)")
    ap.add_argument("--budget", default=None,
                    help="wall time (3s) or route evaluations (4000ev: reproducible); "
                         "default 3s, for the front 1s per plan")
    ap.add_argument("--seed", type=int, default=0, help="random seed")
    ap.add_argument("--stage-hours", type=float, default=None,
                    help="stage duration [h] (default: from the voyage, 12 h for an ocean "
                         "crossing, shorter so a short passage gets ~12 stages)")
    ap.add_argument("--rta-tolerance", default="5m",
                    help="an arrival this much after the RTA (or a port's latest arrival) "
                         "is on time (default 5m; e.g. 0, 90s, 10m)")
    ap.add_argument("--seed-pool", default=None, help="seed pool directory")
    ap.add_argument("--out", default=".", help="output directory")
    ap.add_argument("--name", default=None, help="output file stem (default from ports)")
    ap.add_argument("--no-plot", action="store_true")
    ap.add_argument("--list-methods", action="store_true")
    ap.add_argument("--bathymetry", action="append", default=[], metavar="FILE",
                    help="bathymetry grid (GEBCO/ETOPO/EMODnet NetCDF; repeatable, the finest "
                         "wins where they overlap); the global ETOPO5 grid of Debian's "
                         "ferret-datasets is added when installed")
    ap.add_argument("--no-default-bathymetry", action="store_true",
                    help="do not add the coarse global ETOPO5 grid")
    ap.add_argument("--ukc-margin", type=float, default=1.0, metavar="M",
                    help="under-keel clearance margin [m] on top of draft, squat and "
                         "wave allowance (default 1.0)")
    ap.add_argument("--zones", action="append", default=[], metavar="Z.geojson",
                    help="no-go areas (GeoJSON polygons; property mode hard|penalty, "
                         "penalty_per_nm); repeatable")
    ap.add_argument("--clearance-nm", type=float, default=0.0,
                    help="distance from land [NM] the route check of the plan requires")
    rule = DEFAULT_CLEARANCE
    ap.add_argument("--open-sea-clearance-nm", type=float, default=rule.open_sea_nm,
                    metavar="NM", help="distance from land [NM] the search keeps in open sea "
                    f"(0-5, default {rule.open_sea_nm:g}; 0: off land only)")
    ap.add_argument("--approach-clearance-nm", type=float, default=rule.approach_nm,
                    metavar="NM", help="distance from land [NM] the search keeps within the "
                    "approach zone of the span ends and in narrow water (0-3, default "
                    f"{rule.approach_nm:g})")
    ap.add_argument("--approach-zone-nm", type=float, default=rule.approach_zone_nm,
                    metavar="NM", help="radius [NM] round the span ends (ports, strait "
                    "exits, the ship) where the approach clearance applies (0-200, default "
                    f"{rule.approach_zone_nm:g})")
    ap.add_argument("--approach", action="append", default=[], metavar="FILE.rtz",
                    help="coastal passage from/to a port (RTZ or GeoJSON, e.g. from the "
                         "ECDIS), sailed as given and checked; repeatable")
    return ap


def _climatology(path: str | None):
    """The user's monthly climatology dataset, or None; refused with the reason."""
    if not path:
        return None
    from shiproute_weather.errors import WeatherError
    from shiproute_weather.ingest.coverage import load_climatology

    try:
        return load_climatology(path)
    except WeatherError as exc:
        raise InvalidVoyageError(f"climatology refused: {exc}") from exc


def _progress(p: Progress) -> None:
    best = f"{p.best_objective:.1f}" if p.best_objective == p.best_objective else "none feasible"
    print(f"\rleg {p.leg} gen {p.generation:4d} evals {p.evaluations:7d} best {best} "
          f"({p.elapsed_s:.1f} s)", end="", file=sys.stderr, flush=True)


def main(argv: list[str]) -> int:
    """Entry point of `shiproute plan`."""
    if "--list-methods" in argv:
        print("\n".join(method_names()))
        return 0
    args = build_parser().parse_args(argv)
    from ..io.rtz import validate_rtz, write_rtz
    from ..io.summary import write_geojson, write_json

    try:
        check_options(args, PLAN_OPTIONS, budget_option="--budget")
        risk = risk_option(args.risk, args.p_hs_max, args.p_late_max)
        req = build_request(
            origin=args.origin, destination=args.destination, depart=args.depart, rta=args.rta,
            via=args.via, ship=args.ship, objective=args.objective, method=args.method,
            model=args.model, seed=args.seed, stage_hours=args.stage_hours,
            budget=args.budget or (f"{args.front_points}s" if args.objective == "front"
                                   else "3s"),
            loading=args.loading, fuel_type=args.fuel_type, fuel_price_usd_per_t=args.fuel_price,
            charter_usd_per_day=args.charter_rate, front_points=args.front_points,
            rta_tolerance=args.rta_tolerance)
        forecast = (load_forecast(args.forecast, waves_from_wind=not args.no_wave_estimate)
                    if args.forecast else None)
        # build the sampler outside the budget: --budget is planning time, not file loading
        env_forecast = None
        if forecast is not None:
            from shiproute_weather.sampling.sampler import ForecastSampler

            env_forecast = ForecastSampler(forecast)
        keywords = dict(
            cycle_id=str(forecast.attrs.get("cycle_id", "")) if forecast is not None else "",
            persistence_h=args.persistence_hours, climatology=_climatology(args.climatology),
            bathymetry=args.bathymetry, default_bathymetry=not args.no_default_bathymetry,
            ukc_margin_m=args.ukc_margin, zones=args.zones, clearance_nm=args.clearance_nm,
            open_sea_clearance_nm=args.open_sea_clearance_nm,
            approach_clearance_nm=args.approach_clearance_nm,
            approach_zone_nm=args.approach_zone_nm,
            approaches_given=args.approach, risk=risk)
        from ..geo.full_land import first_builds  # numba kernels: not for `--help`

        built = first_builds()
        warm_s = warm_up(req, keywords)
        print(warm_up_note(warm_s, built), file=sys.stderr)
        if req.objective == "front":
            from .plan_front import run_front

            return run_front(req, env_forecast, args, forecast, keywords)
        plan = run_request(req, env_forecast, seed_pool_dir=args.seed_pool, progress=_progress,
                           **keywords)
        print(file=sys.stderr)
        plan.extra.setdefault("timing_s", {})["process_warm_up"] = round(warm_s, 3)
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        stem = args.name or re.sub(r"[^A-Za-z0-9]+", "_", "_".join(plan.ports)).strip("_")
        rtz = write_rtz(plan, out / f"{stem}.rtz")
        validate_rtz(rtz)
        write_geojson(plan, out / f"{stem}.geojson")
        write_json(plan, out / f"{stem}.json")
        if not args.no_plot:
            from ..io.plots import write_png

            write_png(plan, out / f"{stem}.png", forecast)
            if plan.extra.get("ensemble"):
                from ..io.ensemble_plots import write_ensemble_png

                write_ensemble_png(plan, out / f"{stem}_ensemble.png", forecast)
    except PlannerError as exc:
        print(f"\nshiproute plan: error: {exc}", file=sys.stderr)
        return 2
    print(format_summary(plan))
    print(f"files: {out / stem}.{{rtz,geojson,json{'' if args.no_plot else ',png'}}}")
    return 0 if plan.feasible else 1


def _short(name: str) -> str:
    """Canonical field name without the common prefixes, for one-line summaries."""
    for p in ("sea_surface_", "sea_water_"):
        name = name.replace(p, "")
    return name


def format_summary(plan) -> str:
    """Human-readable plan summary with the baseline beside it."""
    from datetime import UTC, datetime

    def iso(t: float) -> str:
        return datetime.fromtimestamp(t, UTC).strftime("%Y-%m-%d %H:%MZ")

    late_h = (plan.eta_s - plan.rta_s) / 3600.0
    status = "all constraints met" if plan.feasible else "INFEASIBLE: " + "; ".join(
        plan.infeasible_reasons)
    lines = [
        f"route      {' -> '.join(plan.ports)}  ({plan.method}, objective {plan.objective}, "
        f"seed {plan.seed_source})",
        f"fuel       {plan.total_fuel_t:9.1f} t     baseline ({plan.baseline_method}, "
        f"{plan.baseline_rpm:.1f} rpm) {plan.baseline_fuel_t:.1f} t  "
        f"difference {-plan.fuel_saving_t:+.1f} t ({-plan.fuel_saving_pct:+.1f} %)",
        f"distance   {plan.total_distance_nm:9.1f} NM    baseline "
        f"{plan.baseline_distance_nm:.1f} NM",
        f"ETA        {iso(plan.eta_s)}  RTA {iso(plan.rta_s)}  ({late_h:+.1f} h)",
        f"status     {status}" + ("" if plan.baseline_feasible else
                                  "  (baseline violates constraints)"),
        f"compute    {plan.compute_time_s:.2f} s, {plan.generations} generations, "
        f"{plan.evaluations} route evaluations",
    ]
    goal = plan.extra.get("objective") or {}
    if goal.get("name") in ("co2", "cost"):
        extra = (f"  ({goal['co2_factor_t_per_t']:g} t CO2/t {goal['fuel_type']}, "
                 "IMO MEPC.308(73))" if goal["name"] == "co2" else
                 f"  (fuel {goal['fuel_cost_usd']:,.0f} USD at {goal['fuel_price_usd_per_t']:g}"
                 f" USD/t + time {goal['time_cost_usd']:,.0f} USD at "
                 f"{goal['charter_usd_per_day']:,.0f} USD/day)")
        lines.append(f"{goal['name']:<10} {goal['value']:9,.1f} {goal['unit']}{extra}")
    cond = plan.extra.get("loading") or {}
    if cond:
        lines.append(f"loading    {cond['condition']}: drafts {cond['draft_fore_m']:.2f} / "
                     f"{cond['draft_aft_m']:.2f} m fore/aft, {cond['displacement_t']:,.0f} t")
    fc = plan.extra.get("forecast") or {}
    if fc.get("used"):
        lines.append(f"forecast   {fc['valid_from']} .. {fc['valid_to']}: covers "
                     f"{fc['covered_hours']:.1f} h of {fc['voyage_hours']:.1f} h "
                     f"({fc['covered_pct']:.0f} %); fields "
                     f"{', '.join(_short(n) for n in fc['fields'])}")
        for f in fc.get("source_files", []):
            lines.append(f"  from     {f}")
    for row in plan.extra.get("port_calls", ()):
        window = (f"  window {row['earliest']}..{row['latest']}"
                  if row["earliest"] or row["latest"] else "")
        lines.append(f"call       {row['port']:<24s} arrive {row['arrival']}  depart "
                     f"{row['departure']}{window}"
                     + ("" if row["in_window"] else "  LATE"))
    if plan.extra.get("ensemble"):
        from ..ensemble_report import summary_lines

        lines += summary_lines(plan.extra["ensemble"])
    lines += [f"warning    {w}" for w in plan.warnings]
    return "\n".join(lines)
