"""Fleet planning on a real Dask LocalCluster (worker processes): the same plans as planning
the voyages one by one, bit for bit; a worker killed mid-batch loses and duplicates nothing;
bad rows and an unreachable scheduler are reported; a re-run skips what is already planned."""

from __future__ import annotations

import json
import os
import signal
import threading
import time
from datetime import UTC, datetime, timedelta

import pytest

distributed = pytest.importorskip("distributed")

from shiproute_planner.fleet.forecasts import cached_forecast  # noqa: E402
from shiproute_planner.fleet.keys import forecast_key  # noqa: E402
from shiproute_planner.fleet.outputs import VOYAGES_DIR  # noqa: E402
from shiproute_planner.fleet.runner import FleetOptions, run_fleet  # noqa: E402
from shiproute_planner.fleet.voyages import VoyageSpec  # noqa: E402
from shiproute_planner.plan_request import build_request, run_request  # noqa: E402
from shiproute_planner.threads import set_planner_threads  # noqa: E402

SHORT = (("Shanghai", "Busan", 2.0), ("Busan", "Yokohama", 3.0), ("Kaohsiung", "Shanghai", 2.5),
         ("Tokyo", "32.0,150.0", 2.0))  # short passages: cheap plans, a fast test
DEPART0 = datetime(2026, 3, 3, 12, tzinfo=UTC)  # storm_march's reference time


@pytest.fixture(scope="module")
def forecast_file(tmp_path_factory) -> str:
    """storm_march cut to the test passages (20-45 N, 115-155 E, 6 days) as a NetCDF file: the
    forecast-file path of the fleet, and quick for every worker to load."""
    import xarray as xr
    from shiproute_weather.scenarios.catalogue import scenario_path

    path = tmp_path_factory.mktemp("forecast") / "storm_march_cut.nc"
    with xr.open_dataset(scenario_path("storm_march")) as ds:
        cut = ds.sel(latitude=slice(20.0, 45.0), longitude=slice(115.0, 155.0),
                     time=slice("2026-03-03T12:00", "2026-03-09T12:00"))
        cut.load().to_netcdf(path)
    return str(path)


def _voyages(n: int, budget: str = "300ev") -> list[VoyageSpec]:
    out = []
    for k in range(n):
        a, b, days = SHORT[k % len(SHORT)]
        dep = DEPART0 + timedelta(hours=15 * (k // len(SHORT)))
        req = build_request(origin=a, destination=b, depart=dep.isoformat(), rta=f"{days}d",
                            budget=budget, seed=100 + k)
        out.append(VoyageSpec(f"v{k:02d}", f"vessel{k % 7}", k + 2, req, None, f"v{k:02d}"))
    return out


@pytest.fixture(scope="module")
def cluster():
    from shiproute_planner.fleet.runner import WORKER_ENV

    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None, env=WORKER_ENV,
                                  silence_logs=40) as c:
        yield c


def test_cluster_plans_equal_one_by_one(cluster, forecast_file, tmp_path):
    voyages = _voyages(20)
    opts = FleetOptions(out_dir=str(tmp_path), forecasts=(forecast_file,),
                        scheduler=cluster.scheduler_address)
    run = run_fleet(voyages, opts, show_progress=False)
    by_id = {r["voyage_id"]: r for r in run.records}
    assert all(r["status"] == "planned" for r in run.records), run.records
    assert len({r["worker"] for r in run.records}) == 2  # both workers planned
    # all inside the forecast grid and its valid times: the plans state no forecast gap
    assert not any("forecast" in w for r in run.records for w in r["warnings"].split(";"))
    from shiproute_planner.fleet.forecasts import loads

    key = forecast_key(forecast_file)
    with distributed.Client(cluster) as client:  # the forecast was loaded once per worker
        assert list(client.run(loads).values()) == [[key], [key]]
    set_planner_threads(1)
    fc = cached_forecast(forecast_file, forecast_key(forecast_file))
    for v in voyages:
        alone = run_request(v.request, fc.sampler, cycle_id=fc.cycle_id)
        assert by_id[v.voyage_id]["fuel_t"] == alone.total_fuel_t  # bit for bit
        assert by_id[v.voyage_id]["evaluations"] == alone.evaluations
    # outputs: one folder per voyage with the io writers' files and the record
    dirs = sorted((tmp_path / VOYAGES_DIR).iterdir())
    assert len(dirs) == 20
    for d in dirs:
        assert {p.name for p in d.iterdir()} == {"plan.rtz", "plan.geojson", "plan.json",
                                                 "result.json"}
        assert json.loads((d / "plan.json").read_text())["total_fuel_t"] == json.loads(
            (d / "result.json").read_text())["fuel_t"]
    # a re-run with the same inputs plans nothing; a changed row is planned again and its old
    # output replaced
    again = run_fleet(voyages, opts, show_progress=False)
    assert all(r.get("already_planned") for r in again.records) and again.wall_s == 0.0
    changed = [*voyages[:19], VoyageSpec("v19", "vessel5", 21, build_request(
        origin="Busan", destination="Yokohama", depart="2026-03-04T00:00Z", rta="3d",
        budget="200ev"), None, "v19")]
    third = run_fleet(changed, opts, show_progress=False)
    assert sum(not r.get("already_planned") for r in third.records) == 1
    assert len(list((tmp_path / VOYAGES_DIR).glob("v19--*"))) == 1


def test_killed_worker_every_voyage_one_output(cluster, forecast_file, tmp_path):
    voyages = _voyages(12, budget="600ev")
    opts = FleetOptions(out_dir=str(tmp_path), forecasts=(forecast_file,),
                        scheduler=cluster.scheduler_address)
    client = distributed.Client(cluster)
    client.wait_for_workers(2)
    victims: list[int] = []

    def kill_one_worker() -> None:
        """Once a voyage is done, SIGKILL the worker process of a running one."""
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            if any((tmp_path / VOYAGES_DIR).glob("v*")):
                busy = [w for w, keys in client.processing().items() if keys]
                if busy:
                    pid = client.run(os.getpid, workers=[busy[0]])[busy[0]]
                    os.kill(pid, signal.SIGKILL)
                    victims.append(pid)
                    return
            time.sleep(0.05)

    killer = threading.Thread(target=kill_one_worker)
    killer.start()
    run = run_fleet(voyages, opts, show_progress=False)
    killer.join()
    client.close()
    assert victims, "no worker was killed: the test did not test anything"
    assert sorted(r["voyage_id"] for r in run.records) == [v.voyage_id for v in voyages]
    assert all(r["status"] == "planned" for r in run.records), run.records
    for v in voyages:  # exactly one complete output each, no temp folder left
        assert len(list((tmp_path / VOYAGES_DIR).glob(f"{v.voyage_id}--*"))) == 1
    assert not list((tmp_path / VOYAGES_DIR).glob(".tmp-*"))
    assert len(list((tmp_path / VOYAGES_DIR).iterdir())) == len(voyages)


def test_cli_bad_rows_and_unreachable_scheduler(cluster, forecast_file, tmp_path, capsys):
    from shiproute_planner.cli.fleet import main

    f = tmp_path / "fleet.csv"
    f.write_text("vessel,from,to,depart,rta,budget\n"
                 "A,Shanghai,Busan,2026-03-04T00:00Z,2d,150ev\n"
                 "B,Shanghai,Nowhere Port,2026-03-03T00:00Z,2d,150ev\n"
                 "C,Shanghai,Busan,2026-03-03T00:00Z,2026-03-02T00:00Z,150ev\n"
                 'D,"36.2,138.2",Busan,2026-03-04T00:00Z,2d,150ev\n')  # inland Japan
    out = tmp_path / "out"
    code = main([str(f), "--forecast", forecast_file, "--scheduler", cluster.scheduler_address,
                 "--out", str(out), "--quiet"])
    err = capsys.readouterr().err
    assert code == 1  # two rows skipped, one voyage failed
    assert f"{f}:3: B: skipped:" in err and "Nowhere Port" in err
    assert f"{f}:4: C: skipped:" in err and "RTA must be after" in err
    assert "D: failed:" in err and "on land" in err  # failed on a worker, the rest planned
    import csv

    with (out / "fleet_summary.csv").open() as fh:
        rows = {r["voyage_id"]: r for r in csv.DictReader(fh)}
    assert {k: r["status"] for k, r in rows.items()} == {
        "A": "planned", "B": "invalid", "C": "invalid", "D": "failed"}
    assert rows["B"]["reason"].startswith("line 3: ") and "on land" in rows["D"]["reason"]
    assert float(rows["A"]["fuel_t"]) > 0 and rows["A"]["out_dir"]
    assert (out / "fleet_summary.png").stat().st_size > 10_000
    t0 = time.monotonic()
    code = main([str(f), "--scheduler", "tcp://127.0.0.1:9", "--connect-timeout", "2",
                 "--out", str(tmp_path / "x"), "--force"])
    assert code == 2 and time.monotonic() - t0 < 20
    assert "no Dask scheduler answers at tcp://127.0.0.1:9" in capsys.readouterr().err
