"""A fixed passage between two optimised spans (a shoal's deep-water passage) is sailed at
the pace the schedule gives it, not at the RPM the span before it happened to end at."""

from types import SimpleNamespace

import numpy as np
from shiproute_core.units import M_PER_NM, M_S_PER_KNOT
from shiproute_planner.plan_legs import LegRun, scheduled_rpm
from shiproute_planner.plan_setup import make_environment
from shiproute_planner.ship import SeaState
from shiproute_planner.voyage.legs import calm_fuel_rate
from shiproute_planner.voyage.schedule import LegSpec


def test_passage_keeps_the_schedules_pace_after_a_slow_span():
    env, spec = make_environment("bulk_supramax")
    rpm_min, rpm_max = spec.engine.rpm_min, spec.engine.rpm_max
    depart = 1.775e9
    # Buenos Aires -> gate, the Rio de la Plata passage, gate -> Santos: 5 days in all; the
    # first span took 12 h and ended at the slowest RPM
    legs = [LegSpec(name, nm * M_PER_NM) for name, nm in
            (("gate in", 60.0), ("gate out", 111.0), ("Santos", 812.0))]
    prep = SimpleNamespace(schedule=object(), fuel_rate=calm_fuel_rate(env.model, rpm_min,
                                                                       rpm_max),
                           rta_warning="", schedule_legs=legs, ports=[None] * 4,
                           rta_s=depart + 120 * 3600.0, env=env)
    run = LegRun(depart + 12 * 3600.0, [0.0] * 3, [])
    run.results.append(SimpleNamespace(legs={"rpm": np.array([[rpm_min]])}))
    rpm = scheduled_rpm(prep, run, 1)
    # one fuel-rate curve for every leg and no window binding: the fuel-optimal schedule
    # sails the legs left at one speed, (111 + 812) NM in the 108 h left
    speed_kn = float(env.model.evaluate(np.array([rpm]), np.zeros(1),
                                        SeaState.calm(1)).stw_m_s[0]) / M_S_PER_KNOT
    assert abs(speed_kn - 923.0 / 108.0) < 0.03 * 923.0 / 108.0
    assert rpm > rpm_min + 5.0
