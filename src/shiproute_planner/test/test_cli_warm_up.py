"""A one-shot `shiproute plan` process must give the search its budget: its one-off set-up
(compiled kernels, land and depth maps, sea lanes, coastal passages) is done before the
budget's clock, as the planner node does at start. Counted inside the budget it left an
ocean crossing 0 generations of a 3-s budget (the plan was the best seed track)."""

from __future__ import annotations

import json

from shiproute_planner.cli.plan import main as plan_main


def test_cli_plan_warms_up_outside_the_budget_and_searches(tmp_path, capsys):
    code = plan_main(["--from", "Busan", "--to", "Long Beach", "--depart",
                      "2026-03-03T18:00Z", "--rta", "13d", "--out", str(tmp_path),
                      "--no-plot", "--budget", "3s"])
    assert code in (0, 1)
    err = capsys.readouterr().err
    assert "warm-up:" in err and "before the budget's clock" in err
    (path,) = tmp_path.glob("*.json")
    doc = json.loads(path.read_text())
    # a GA generation is one population (~100 routes): an ocean crossing that kept its
    # budget for the search makes many; the best seed alone is generation 0
    assert doc["generations"] >= 5, doc["generations"]


def test_warm_up_names_the_land_rasters_it_will_build_for_a_new_machine(tmp_path,
                                                                         monkeypatch):
    """An empty data directory (a new machine) lacks every land raster and the search's
    distance to the coast: the warm-up says it builds them (~40 s at full resolution, once);
    once stored, it says nothing of them."""
    from shiproute_planner.cli.warm_up import warm_up_note
    from shiproute_planner.geo.coast_distance import COAST_DISTANCE_VERSION
    from shiproute_planner.geo.full_land import first_builds
    from shiproute_planner.geo.gshhg import finest_resolution
    from shiproute_planner.geo.landmask import cached_array_name

    monkeypatch.setenv("SHIPROUTE_DATA_DIR", str(tmp_path))
    wanted = {"i", finest_resolution()}
    built = first_builds()
    assert len(built) == len(wanted) + 1
    assert "intermediate-resolution land raster" in " ".join(built)
    assert "distance to the coast" in built[-1]
    note = warm_up_note(2.0, built)
    assert "for this machine (once)" in note and built[0] in note
    for res in wanted:
        (tmp_path / cached_array_name("landmask", res, 0.05)).write_bytes(b"")
    assert first_builds() == built[-1:]
    (tmp_path / cached_array_name(f"coastdistance{COAST_DISTANCE_VERSION}", "i", 0.05)
     ).write_bytes(b"")
    assert first_builds() == ()
    assert "for this machine" not in warm_up_note(2.0, first_builds())
