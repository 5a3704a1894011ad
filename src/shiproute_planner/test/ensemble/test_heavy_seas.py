"""Heave-to above the ship's wave limit and the fuel to still meet the RTA (`route.heavy_seas`):
the bookkeeping against hand-worked voyages, and the propeller law's recovery fuel against an
exact re-solve with the ship model."""

from __future__ import annotations

import numpy as np
import pytest
from shiproute_planner.route.evaluation import RouteEvaluation
from shiproute_planner.route.heavy_seas import HeaveTo, heave_to_of, member_voyage
from shiproute_planner.route.problem import RouteLimits, RouteProblem
from shiproute_planner.ship import SeaState, fast_model, load_ship

H = 3600.0
HEAVE = HeaveTo(rpm=28.0, fuel_t_per_h=0.5)


def _voyage(hs_m: list[float], rta_h: float, load: float, stage_h: float = 12.0):
    """Four-leg voyage: legs of `stage_h` at 10 t each and engine load `load`, seas `hs_m`,
    ship limit 8 m, planned ETA at 4 x `stage_h`, RTA `rta_h` after departure."""
    n = len(hs_m)
    problem = RouteProblem(0.0, 0.0, 10.0, 0.0, 0.0, rta_h * H,
                           RouteLimits(rpm_min=28.0, rpm_max=90.0, max_hs_m=8.0))
    t = np.arange(n + 1, dtype=float)[None, :] * stage_h * H
    legs = {"duration_s": np.full((1, n), stage_h * H), "hs_m": np.array([hs_m], dtype=float),
            "fuel_t": np.full((1, n), 10.0), "engine_load": np.full((1, n), load)}
    z = np.zeros(1)
    ev = RouteEvaluation(np.zeros((1, n + 1)), np.zeros((1, n + 1)), t, legs,
                         np.zeros((1, n), np.uint32), np.array([10.0 * n]), z, t[:, -1],
                         np.zeros(1, np.uint32), z, np.array([10.0 * n]))
    return member_voyage(problem, ev, HEAVE)


def test_calm_on_time_member_is_unchanged():
    v = _voyage([3.0, 3.0, 3.0, 3.0], rta_h=48.0, load=0.5)
    assert v.fuel_t[0] == 40.0 and v.eta_s[0] == 48.0 * H and v.heave_to_s[0] == 0.0
    assert v.speed_factor[0] == 1.0 and not v.unrecoverable[0]


def test_heave_to_absorbed_by_slack_costs_only_the_heave_to_fuel():
    """12 h hove to, 24 h of slack: on time without speeding up, 12 h x 0.5 t/h added."""
    v = _voyage([3.0, 9.0, 3.0, 3.0], rta_h=72.0, load=0.5)
    assert v.heave_to_s[0] == 12 * H and v.eta_s[0] == 60.0 * H
    assert v.fuel_t[0] == pytest.approx(40.0 + 6.0)
    assert v.recovery_fuel_t[0] == 0.0


def test_heave_to_without_slack_is_recovered_on_the_rest_of_the_voyage():
    """Hove to on leg 1 (12 h), no slack: the 36 h from the deferred leg on are sailed in
    24 h, speed x 1.5, the 30 t of those legs x 1.5^2; the engine at 25 % load can (1.5^3 x
    0.25 = 0.84 MCR): on time."""
    v = _voyage([3.0, 9.0, 3.0, 3.0], rta_h=48.0, load=0.25)
    assert v.speed_factor[0] == pytest.approx(1.5)
    assert v.recovery_fuel_t[0] == pytest.approx(30.0 * 1.25)
    assert v.fuel_t[0] == pytest.approx(40.0 + 6.0 + 37.5)
    assert v.eta_s[0] == 48.0 * H and not v.unrecoverable[0]


def test_delay_beyond_mcr_arrives_late_by_what_mcr_cannot_make_up():
    """At 50 % load the engine reaches MCR at speed x 0.5^(-1/3) = 1.26: the 36 h take
    36 / 1.26 = 28.57 h, so the member is 4.57 h late, its 30 t x 1.26^2."""
    v = _voyage([3.0, 9.0, 3.0, 3.0], rta_h=48.0, load=0.5)
    k = 0.5 ** (-1.0 / 3.0)
    assert v.speed_factor[0] == pytest.approx(k)
    assert v.eta_s[0] == pytest.approx(48.0 * H + 12 * H - 36 * H * (1 - 1 / k))
    assert v.recovery_fuel_t[0] == pytest.approx(30.0 * (k**2 - 1))
    assert v.unrecoverable[0]


def test_weather_lateness_without_heave_to_is_spread_over_the_whole_voyage():
    """Late by 6 h from head seas under the limit: the 48 h voyage in 42 h, fuel x (48/42)^2."""
    v = _voyage([6.0, 7.0, 7.5, 6.0], rta_h=42.0, load=0.4)
    assert v.heave_to_s[0] == 0.0
    assert v.fuel_t[0] == pytest.approx(40.0 * (48.0 / 42.0) ** 2)
    assert v.eta_s[0] == 42.0 * H


def test_heave_to_fuel_is_the_ships_own_at_its_minimum_rpm():
    ship = load_ship("container_4600teu")
    heave = heave_to_of(ship)
    perf = fast_model(ship).evaluate(np.array([ship.engine.rpm_min]), np.array([0.0]),
                                     SeaState.calm(1))
    assert heave.rpm == ship.engine.rpm_min
    assert heave.fuel_t_per_h == pytest.approx(float(perf.fuel_t_per_h[0]))
    # dead slow burns a few percent of the service fuel rate (power ~ RPM^3: (28/~80)^3 ~ 4 %)
    service = fast_model(ship).evaluate(np.array([0.85 * ship.engine.rpm_max]),
                                        np.array([0.0]), SeaState.calm(1))
    assert 0.0 < heave.fuel_t_per_h < 0.1 * float(service.fuel_t_per_h[0])


SEAS = {"calm": {}, "head_4m": dict(hs=4.0, from_deg=0.0, period=8.0, wind_v=-12.0),
        "head_6m": dict(hs=6.0, from_deg=0.0, period=10.0, wind_v=-18.0),
        "following_6m": dict(hs=6.0, from_deg=180.0, period=10.0, wind_v=18.0)}


@pytest.mark.parametrize("sea", sorted(SEAS))
@pytest.mark.parametrize("delay_share", [0.05, 0.1, 0.2])
def test_propeller_law_recovery_is_within_its_bound_of_an_exact_re_solve(sea, delay_share):
    """The remaining distance sailed in T_r at the planned RPM (75 % of the rated RPM), then
    in T_r - D: the exact fuel re-solves the RPM for the speed k = T_r / (T_r - D) times
    higher with the ship model (Holtrop-Mennen, wind and wave added resistance, B-series
    propeller, SFOC curve); the approximation is F_r k^2.

    Fuel per distance goes with R / (eta_D) x SFOC. The law takes R ~ V^2. Calm-water
    resistance rises between V^2 (friction) and V^3 (wave making at service Froude numbers),
    the added resistance of wind and waves hardly with speed (it is there at V = 0), so
    R(kV) / R(V) lies between 1 and k^3: the exact over the approximated fuel within
    [k^-2, k], and a few percent more for the propulsive efficiency and SFOC moving with the
    load (5 % allowed)."""
    ship = load_ship("container_4600teu")
    model = fast_model(ship)
    s = SEAS[sea]
    state = (SeaState.calm(1) if not s else
             SeaState.from_arrays(wind_wave_hs_m=np.array([s["hs"]]),
                                  wind_wave_from_deg=np.array([s["from_deg"]]),
                                  wind_wave_period_s=np.array([s["period"]]),
                                  wind_v_m_s=np.array([s["wind_v"]])))
    heading = np.array([0.0])
    rpm0 = np.array([0.75 * ship.engine.rpm_max])
    p0 = model.evaluate(rpm0, heading, state)
    t_r = 240 * H
    k = 1.0 / (1.0 - delay_share)
    approx = float(p0.fuel_t_per_h[0]) * t_r / H * k**2
    rpm1 = model.rpm_for_speed(p0.stw_m_s * k, heading, state)
    p1 = model.evaluate(rpm1, heading, state)
    assert float(p1.stw_m_s[0]) == pytest.approx(float(p0.stw_m_s[0]) * k, rel=1e-3)
    assert float(p1.engine_load[0]) <= 1.0  # the speed-up stays within MCR here
    exact = float(p1.fuel_t_per_h[0]) * t_r * (1.0 - delay_share) / H
    assert k**-2 * 0.95 <= exact / approx <= k * 1.05


def test_member_above_the_limit_everywhere_heaves_to_and_cannot_make_the_rta(
        over_limit_members, land_mask):
    """Busan -> Long Beach on two members: a 5 m/s breeze with a 1.5 m sea, and a 9 m sea
    (above the 4,600 TEU ship's 8 m limit) over the whole grid. In the second every stage in
    the forecast is spent hove to: days lost on a 13-day RTA that no speed up to MCR makes
    good, so the member is late for every candidate (at MCR on what is left); the calm member
    never heaves to."""
    from shiproute_planner.plan_setup import make_environment, route_limits, to_posix_s
    from shiproute_planner.route.encoding import gene_bounds, join_genes
    from shiproute_planner.route.fast_eval import fast_evaluator
    from shiproute_planner.route.member_eval import risk_evaluate_outcomes
    from shiproute_planner.route.risk import RiskSpec
    from shiproute_planner.route.seeding import great_circle_track
    from shiproute_weather.sampling.sampler import ForecastSampler

    sampler = ForecastSampler(over_limit_members, member_dtype=np.float32)
    env, spec = make_environment("container_4600teu", sampler)
    d = to_posix_s("2026-03-03T18:00Z")
    problem = RouteProblem(129.5, 34.8, -118.5, 33.5, d, d + 13 * 86400.0, route_limits(spec))
    n = problem.n_stages
    lo, hi = gene_bounds(problem)
    g_lon, g_lat = great_circle_track(problem, n + 1)
    az = np.degrees(np.arctan2(np.diff(g_lon), np.diff(g_lat)))  # roughly east: no land
    rpm = np.linspace(lo[n] + 0.3 * (hi[n] - lo[n]), hi[n], 8)[:, None] * np.ones(n + 1)
    x = join_genes(np.repeat(az[None, :], 8, axis=0), rpm)
    fast = fast_evaluator(problem, env, land_mask)
    _, out = risk_evaluate_outcomes(fast, RiskSpec(), x)
    voyage = out.voyage
    assert voyage is not None
    heave = voyage.heave_to_s.reshape(2, -1)
    assert np.all(heave[0] == 0.0)
    assert np.all(heave[1] >= 5 * 86400.0)  # the grid spans more than 5 days of the voyage
    assert np.all(voyage.unrecoverable.reshape(2, -1)[1]) and np.all(out.late[1])
    assert np.all(out.probability(out.late) >= 0.5)  # at least that member's weight
    assert np.all(out.hs_exceeded[1]) and not np.any(out.hs_exceeded[0])


@pytest.mark.parametrize("late_share", [0.04, 0.1])
def test_voyage_recovery_is_within_its_bound_of_a_re_solve_of_the_rpms(head_sea_forecast,
                                                                       late_share):
    """A whole voyage, Busan -> Long Beach in a uniform 12 m/s head wind and 4 m head sea,
    sailed at one RPM that makes it late by `late_share` of its time under way: the
    approximation (fuel x k^2, k = T / (T - D)) against the exact re-solve, the same genes
    with every RPM scaled (bisection) until the compiled route model arrives on the RTA.
    Same physics bound as the ship-model test: [k^-2, k] and 5 %."""
    from shiproute_planner.plan_setup import make_environment, route_limits, to_posix_s
    from shiproute_planner.route.encoding import join_genes
    from shiproute_planner.route.fast_eval import fast_evaluator
    from shiproute_planner.route.seeding import great_circle_track
    from shiproute_weather.sampling.sampler import ForecastSampler

    env, spec = make_environment("container_4600teu", ForecastSampler(head_sea_forecast))
    d = to_posix_s("2026-03-03T18:00Z")
    base = RouteProblem(129.5, 34.8, -118.5, 33.5, d, d + 13 * 86400.0, route_limits(spec))
    n = base.n_stages
    g_lon, g_lat = great_circle_track(base, n + 1)
    az = np.degrees(np.arctan2(np.diff(g_lon) * np.cos(np.radians(g_lat[:-1])), np.diff(g_lat)))

    def sail(problem: RouteProblem, rpm: float) -> RouteEvaluation:
        x = join_genes(az[None, :n], np.full((1, n + 1), rpm))
        return fast_evaluator(problem, env, None).evaluate(x)

    ev = sail(base, 70.0)
    under_way = float(ev.eta_s[0]) - d
    rta = d + under_way * (1.0 - late_share)
    problem = RouteProblem(129.5, 34.8, -118.5, 33.5, d, rta, route_limits(spec), n_stages=n)
    ev = sail(problem, 70.0)
    approx = member_voyage(problem, ev, HEAVE)
    assert approx.heave_to_s[0] == 0.0 and not approx.unrecoverable[0]
    assert approx.fuel_t[0] > ev.fuel_t[0]  # the recovery is counted
    lo, hi = 70.0, 70.0 * 1.4
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if sail(problem, mid).eta_s[0] > rta else (lo, mid)
    exact = sail(problem, hi)
    assert abs(float(exact.eta_s[0]) - rta) < 600.0
    k = under_way / (under_way - (float(ev.eta_s[0]) - rta))
    ratio = float(exact.fuel_t[0]) / float(approx.fuel_t[0])
    assert k**-2 * 0.95 <= ratio <= k * 1.05


def test_plan_states_heave_to_and_added_fuel_in_its_warning_and_summary():
    """Four equal members, two hove to (12 h, 24 h) with 40 t and 100 t added: P(heave-to)
    0.50, mean added fuel (40 + 100) / 4 = 35.0 t, worst 24 h and 100.0 t."""
    from shiproute_planner.ensemble_report import heavy_seas_sentence, summary_lines
    from shiproute_planner.route.heavy_seas import HEAVY_SEAS_MODEL

    w = np.full(4, 0.25)
    heavy = {"model": HEAVY_SEAS_MODEL, "p_heave_to": 0.5, "heave_to_h": [0.0, 12.0, 0.0, 24.0],
             "added_fuel_t": [0.0, 40.0, 0.0, 100.0], "p_rta_unrecoverable": 0.25}
    said = heavy_seas_sentence(heavy, w)
    assert "P(heave-to) 0.50" in said and "hove to up to 24 h and up to 100.0 t added" in said
    assert "mean fuel added by heave-to and RTA recovery 35.0 t" in said
    assert "P(RTA not recoverable even at MCR) 0.25" in said and HEAVY_SEAS_MODEL in said
    spread = {"min": [1.0], "median": [2.0], "max": [9.0]}
    block = {"members": 4, "kind": "ensemble", "risk_measure": "cvar:0.9", "weights": list(w),
             "fuel_t": {"p10": 1.0, "p50": 2.0, "p90": 3.0, "mean": 2.0},
             "eta_s": {"p10": 0.0, "p50": 0.0, "p90": 0.0}, "p_hs_violation": 0.5,
             "p_late": 0.25, "p_any_violation": 0.5, "heavy_seas": heavy,
             "legs": {"hs_m": spread, "wind_speed_m_s": spread}}
    line = [x for x in summary_lines(block) if "heavy seas" in x]
    assert line == ["  heavy seas P(heave-to) 0.50, fuel added to meet the RTA mean 35.0 t, "
                    "P(RTA not recoverable) 0.25"]
