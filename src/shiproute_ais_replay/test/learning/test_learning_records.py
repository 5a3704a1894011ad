"""Records in: CSV logs with units in the header, bags, and their errors."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from shiproute_ais_replay.learning.records import RecordsError, read_csv, read_records
from shiproute_ais_replay.learning.synth import write_bag, write_csv

HEADER = ("time_utc,latitude_deg,longitude_deg,sog_kn,cog_deg,heading_deg,shaft_rpm,"
          "fuel_rate_kg_per_h,draft_fore_m,draft_aft_m,remarks")


def _write(tmp_path: Path, header: str, rows: list[str]) -> Path:
    p = tmp_path / "log.csv"
    p.write_text("\n".join([header, *rows]) + "\n", encoding="utf-8")
    return p


def test_csv_units_are_converted_and_unknown_columns_ignored(tmp_path: Path) -> None:
    p = _write(tmp_path, HEADER, ["2026-03-05T00:00:00Z,35,160,17,90,91,75,2300,11.5,12.5,ok",
                                  "2026-03-05T00:01:00Z,35,160.01,17,90,91,75,,11.5,12.5,"])
    c = read_csv(p)
    assert c["fuel_rate_t_per_h"][0] == pytest.approx(2.3)  # kg/h -> t/h
    assert np.isnan(c["fuel_rate_t_per_h"][1])  # empty cell = missing, not zero
    assert c["time_s"][1] - c["time_s"][0] == pytest.approx(60.0)
    assert np.isnan(c["stw_kn"]).all()  # no log column: derived later from SOG - current


def test_csv_without_fuel_or_rpm_column_is_refused(tmp_path: Path) -> None:
    p = _write(tmp_path, HEADER.replace(",fuel_rate_kg_per_h", "").replace(",shaft_rpm", ""),
               ["2026-03-05T00:00:00Z,35,160,17,90,91,11.5,12.5,ok"])
    with pytest.raises(RecordsError, match=r"shaft: shaft_rpm or shaft_speed_rps.*fuel: "):
        read_csv(p)


def test_csv_column_without_unit_is_refused(tmp_path: Path) -> None:
    p = _write(tmp_path, HEADER.replace("fuel_rate_kg_per_h", "fuel_rate"),
               ["2026-03-05T00:00:00Z,35,160,17,90,91,75,2300,11.5,12.5,ok"])
    with pytest.raises(RecordsError, match=r"column 'fuel_rate' does not state a known unit"):
        read_csv(p)
    p = _write(tmp_path, HEADER.replace("sog_kn", "sog_mph"),
               ["2026-03-05T00:00:00Z,35,160,17,90,91,75,2300,11.5,12.5,ok"])
    with pytest.raises(RecordsError, match=r"'sog_mph'.*sog_kn, sog_m_s"):
        read_csv(p)


def test_bag_and_csv_carry_the_same_records(tmp_path: Path) -> None:
    from shiproute_ais_replay.learning.records import COLUMNS, Records

    n = 50
    t = 1.77e9 + 60.0 * np.arange(n)
    cols = {c: np.linspace(1.0, 2.0, n) for c in COLUMNS}
    cols.update(time_s=t, voyage=np.zeros(n), water_depth_m=np.full(n, np.nan))
    cols["fuel_rate_t_per_h"][7] = np.nan
    rec = Records(cols, ("made",))
    write_csv(rec, tmp_path / "r.csv")
    write_bag(rec, tmp_path / "bag")
    a = read_records([tmp_path / "r.csv"]).columns
    b = read_records([tmp_path / "bag"]).columns
    for k in ("time_s", "sog_kn", "shaft_rpm", "fuel_rate_t_per_h", "draft_aft_m"):
        np.testing.assert_allclose(a[k], cols[k], rtol=1e-5)
        np.testing.assert_allclose(b[k], cols[k], rtol=1e-12)
    assert np.isnan(b["rudder_angle_deg"]).all()  # not a ShipState field


def test_voyages_split_at_long_pauses_and_per_file(tmp_path: Path) -> None:
    rows = [f"{1.77e9 + 60 * i + (8 * 3600 if i >= 5 else 0)},35,160,17,90,91,75,2.3,11,12"
            for i in range(10)]
    p = tmp_path / "a.csv"
    p.write_text("time_s,latitude_deg,longitude_deg,sog_kn,cog_deg,heading_deg,shaft_rpm,"
                 "fuel_rate_t_per_h,draft_fore_m,draft_aft_m\n" + "\n".join(rows) + "\n")
    v = read_records([p]).columns["voyage"]
    assert list(v) == [0] * 5 + [1] * 5
    with pytest.raises(RecordsError, match="do not exist"):
        read_records([tmp_path / "missing.csv"])


def test_learn_cli_refuses_records_without_fuel_and_writes_nothing(tmp_path: Path,
                                                                   capsys) -> None:
    from shiproute_ais_replay.learning.cli import main

    p = _write(tmp_path, HEADER.replace(",fuel_rate_kg_per_h", ""),
               ["2026-03-05T00:00:00Z,35,160,17,90,91,75,11.5,12.5,ok"])
    out = tmp_path / "model.nc"
    rc = main(["learn", str(p), "--forecast", "storm_march", "--out", str(out)])
    err = capsys.readouterr().err
    assert rc == 2 and "fuel: fuel_rate_t_per_h" in err and "Traceback" not in err
    assert not out.exists() and not list(tmp_path.glob("model.nc*"))
