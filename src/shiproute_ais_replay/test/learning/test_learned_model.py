"""Learning a fouled ship from its records: accuracy on later voyages, model file, fallback,
tabulation into the planner's fast path, plans sailed by the true ship, bad input."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from shiproute_ais_replay.learning.cleaning import CleaningConfig, clean
from shiproute_ais_replay.learning.records import join_met
from shiproute_ais_replay.learning.synth import (
    Corruption,
    HullChange,
    simulate_fleet_records,
    true_ship,
)
from shiproute_planner.learned import ModelFileError, TrainingDataError, WrongShipError
from shiproute_planner.learned.features import sea_of
from shiproute_planner.learned.model import LearnedModel
from shiproute_planner.learned.tables import agreement, learned_fast_model
from shiproute_planner.learned.train import TrainConfig, train
from shiproute_planner.ship import load_ship

CHANGE = HullChange()  # +15 % frictional resistance, 1.5 m more trim by the stern
FAULTS = Corruption()


@pytest.fixture(scope="module")
def learned(tmp_path_factory):
    from shiproute_weather.scenarios.catalogue import scenario_dataset

    ship = load_ship("container_4600teu")
    ds = scenario_dataset("storm_march")
    start = float(ds["time"].values[0].astype("datetime64[s]").astype(float)) + 3600.0
    rec = simulate_fleet_records(ship, ds, 5, start, seed=3, legs=4, leg_nm=150.0,
                                 change=CHANGE, corruption=FAULTS)
    seg, report = clean(rec, join_met(rec, [ds]), CleaningConfig(breadth_m=ship.hull.breadth_m))
    model = train(ship, seg, TrainConfig(members=3, seed=0), report)
    path = tmp_path_factory.mktemp("learned") / "model.nc"
    model.save(path)
    return ship, ds, seg, report, model, path


def test_cleaning_counts_every_fault_kind(learned) -> None:
    _, _, _, report, _, _ = learned
    d = report["dropped_by_rule"]
    for rule in ("incomplete", "stuck_value", "rudder", "rpm_std", "chauvenet"):
        assert d[rule] > 0, rule  # each injected fault kind is caught by its rule
    assert report["records_kept"] + sum(d.values()) == report["records_in"]


def test_held_out_later_voyages_beat_003_and_the_ship_file(learned) -> None:
    _, _, _, _, model, _ = learned
    m = model.report["metrics"]
    assert m["test_voyages"] == [3, 4]  # the latest voyages are held out
    assert m["fuel_mre_pct"] <= 3.0  # 003: 5.94 %
    assert m["rpm_mre_pct"] <= 1.0  # 003: 1.01 %
    # the ship file's model misses the fouled hull by more than the learned model's error
    assert m["physics_fuel_mre_pct"] > 5.0
    assert m["physics_fuel_mre_pct"] > 3 * m["fuel_mre_pct"]


def test_model_file_round_trip_and_identity(learned, tmp_path: Path) -> None:
    ship, _, seg, _, model, path = learned
    back = LearnedModel.load(path)
    idx = np.arange(40)
    sea = sea_of({k: v[idx] for k, v in seg.items()})
    args = (seg["stw_kn"][idx], seg["heading_deg"][idx], seg["draft_fore_m"][idx],
            seg["draft_aft_m"][idx], sea)
    np.testing.assert_allclose(back.predict(ship, *args).fuel_t_per_h,
                               model.predict(ship, *args).fuel_t_per_h, rtol=1e-12)
    with pytest.raises(WrongShipError, match="trained for ship 'container_4600teu'"):
        learned_fast_model(load_ship("vlcc_270k"), back)
    bogus = tmp_path / "profile.nc"
    import xarray as xr

    xr.Dataset({"a": ("x", [1.0])}).to_netcdf(bogus)
    with pytest.raises(ModelFileError, match="not a shiproute learned model"):
        LearnedModel.load(bogus)


def test_outside_the_training_range_the_model_is_the_physics_model(learned) -> None:
    ship, _, seg, _, model, _ = learned
    i = int(np.argmin(seg["time_s"]))  # a training segment: inside every range
    one = {k: np.repeat(v[i:i + 1], 3) for k, v in seg.items()}
    hs = float(np.hypot(one["wind_wave_hs_m"][0], one["swell_hs_m"][0]))
    hi = model.report["training_ranges"]["hs_m"][1]
    sd = model.x_std[5] * model.fallback_std
    scale = np.array([hs, hi + 0.5 * sd, hi + 1.5 * sd]) / hs  # same period and direction
    one["wind_wave_hs_m"] = one["wind_wave_hs_m"] * scale
    one["swell_hs_m"] = one["swell_hs_m"] * scale
    p = model.predict(ship, one["stw_kn"], one["heading_deg"], one["draft_fore_m"],
                      one["draft_aft_m"], sea_of(one))
    assert p.weight[0] == 1.0 and 0.0 < p.weight[1] < 1.0 and p.weight[2] == 0.0
    assert p.rpm[2] == p.physics_rpm[2] and p.fuel_t_per_h[2] == p.physics_fuel_t_per_h[2]
    assert p.rpm[0] != p.physics_rpm[0]  # inside, the learned correction applies


def test_tabulated_model_agrees_with_the_learned_model(learned) -> None:
    ship, _, seg, _, model, _ = learned
    fm = learned_fast_model(ship, model)
    idx = np.flatnonzero(seg["voyage"] == seg["voyage"].max())
    sea = sea_of({k: v[idx] for k, v in seg.items()})
    a = agreement(fm, model, ship, seg["stw_kn"][idx], seg["heading_deg"][idx],
                  model.reference_draft_fore_m, model.reference_draft_aft_m, sea)
    # the tables carry the learned ship through a few fitted factors, not every wiggle
    assert a["rpm_mean_diff_pct"] < 1.0
    assert a["fuel_mean_diff_pct"] < 2.5
    # and it recovered the fouling: calm resistance 10-25 % above the ship file's
    f = fm.calibration["calm_resistance_factor_at_training_speeds"]
    assert all(1.08 < x < 1.3 for x in f)


def test_plan_with_the_learned_model_serves_the_true_ship_better(learned) -> None:
    from shiproute_planner.learned.reevaluate import reevaluate
    from shiproute_planner.planning import plan_voyage
    from shiproute_weather.sampling.sampler import ForecastSampler

    ship, ds, _, _, model, path = learned
    sampler = ForecastSampler(ds)
    c = ship.condition
    mean = 0.5 * (model.reference_draft_fore_m + model.reference_draft_aft_m)
    _, truth = true_ship(ship, CHANGE, mean - FAULTS.draft_bias_m
                         - 0.5 * (c.draft_fore_m + c.draft_aft_m))
    out = {}
    for choice in ("physics", f"learned:{path}"):
        plan = plan_voyage("36.0,160.0", "38.0,195.0", "2026-03-10T00:00Z", "2026-03-15T00:00Z",
                           ship, sampler, budget_s=1.5, seed=0, ship_model=choice,
                           max_generations=60, with_baseline=False)
        out[choice.split(":")[0]] = (plan, reevaluate(plan, truth, sampler))
    (_, o_phys), (p_learn, o_learn) = out["physics"], out["learned"]
    assert any("learned from records" in w for w in p_learn.warnings)
    assert o_learn.fuel_t < o_phys.fuel_t or abs(o_learn.late_h) < abs(o_phys.late_h)
    # the learned plan's own fuel estimate is what the true ship burns (within 3 %)
    assert p_learn.total_fuel_t == pytest.approx(o_learn.fuel_t, rel=0.03)


def test_too_few_clean_segments_is_a_clear_error_and_nothing_is_written(learned,
                                                                      tmp_path: Path) -> None:
    ship, _, seg, _, _, _ = learned
    few = {k: v[:100] for k, v in seg.items()}
    out = tmp_path / "m.nc"
    with pytest.raises(TrainingDataError, match=r"only 100 clean segments; training needs at "
                                                r"least 150"):
        train(ship, few).save(out)
    assert not out.exists()


def test_drift_shows_the_fouling_against_physics_and_none_against_the_learned_model(
        learned, tmp_path: Path) -> None:
    from shiproute_ais_replay.learning.drift import daily, drift_table, plot
    from shiproute_planner.ship import fast_model

    ship, _, seg, _, model, _ = learned
    vs_physics = daily(drift_table(seg, fast_model(ship)))
    # +15 % frictional resistance and more trim: more fuel for the speed, less speed for the
    # RPM than the ship file says (cubic law: ~10 % power is ~3 % speed)
    assert vs_physics["excess_fuel_mean_pct"] > 5.0
    assert vs_physics["speed_loss_mean_pct"] < -1.5
    table = drift_table(seg, learned_fast_model(ship, model), model)
    vs_learned = daily(table)
    assert abs(vs_learned["excess_fuel_mean_pct"]) < 1.5
    assert abs(vs_learned["speed_loss_mean_pct"]) < 0.5
    plot(table, vs_learned, tmp_path / "drift.png", "test")
    assert (tmp_path / "drift.png").stat().st_size > 10_000
