"""`shiproute ship` subcommand and the `shiproute bench ship` script (smoke: they run).

Marked slow: both use the fast model, whose numba kernel compiles on first use.
"""

import json

import pytest
import xarray as xr
from shiproute_planner.cli.ship import main as ship_main
from shiproute_planner.experiments.bench.ship import hm_errors
from shiproute_planner.experiments.bench.ship import main as bench_main

pytestmark = pytest.mark.slow


def test_ship_cli_list_show_profile(tmp_path, capsys):
    assert ship_main(["list"]) == 0
    assert "container_4600teu" in capsys.readouterr().out
    assert ship_main(["show", "vlcc_270k", "--condition", "ballast"]) == 0
    shown = json.loads(capsys.readouterr().out)
    assert shown["condition"]["name"] == "ballast"
    out = tmp_path / "p.nc"
    assert ship_main(["profile", "bulk_supramax", str(out), "--n-rpm", "3"]) == 0
    ds = xr.load_dataset(out)
    assert ds.sizes["rpm"] == 3 and float(ds["fuel_t_per_h"].min()) > 0
    assert ship_main(["show", "no_such_ship"]) == 2


def test_bench_prints_one_json_object(capsys):
    assert bench_main(["--json", "--legs", "2000", "--check-legs", "200"]) == 0
    result = json.loads(capsys.readouterr().out)
    for key in ("hm_max_rel_err", "speed_kn_at_77rpm_calm", "fuel_t_per_day_at_77rpm_calm",
                "leg_evals_per_s", "fast_model_max_rel_err"):
        assert key in result
    assert result["hm_max_rel_err"] < 0.01
    assert max(hm_errors().values()) == result["hm_max_rel_err"]
