"""Fleet voyages file: good rows become requests, bad rows are reported with their line number
and reason and skipped while the rest plan; a file without a required column is an error."""

from __future__ import annotations

import pytest
from shiproute_planner.fleet.errors import VoyageFileError
from shiproute_planner.fleet.voyages import read_voyages
from shiproute_planner.plan_request import Budget
from shiproute_planner.plan_setup import to_posix_s

HEADER = "vessel,from,to,depart,rta,ship,via,budget\n"


def test_bad_rows_are_skipped_with_line_and_reason(tmp_path):
    f = tmp_path / "fleet.csv"
    f.write_text(
        HEADER
        + "# comment lines and blank lines are not rows\n"
        + "MV Alpha,Busan,Long Beach,2026-03-03T18:00Z,13d,,,4000ev\n"  # line 3
        + "MV Bravo,Busan,Atlantis Harbour,2026-03-03T18:00Z,13d,,,\n"  # 4 unknown port
        + "MV Charlie,Busan,Long Beach,2026-03-10T00:00Z,2026-03-09T00:00Z,,,\n"  # 5 RTA early
        + "\n"
        + "MV Delta,Busan,,2026-03-03T18:00Z,13d,,,\n"  # 7 missing value
        + "MV Echo,Shanghai,Busan,2026-03-04T00:00Z,2d,vlcc_270k,,90s\n"  # 8
        + "MV Foxtrot,Busan,Long Beach,2026-03-03T18:00Z,13d,no_such_ship,,\n"  # 9
        + "MV Golf,Busan,Long Beach,yesterday,13d,,,\n"  # 10
        + "MV Hotel,Busan,Long Beach,2026-03-03T18:00Z,13d,,Honolulu@2026-03-09T00:00Z,\n")
    table = read_voyages(f)
    assert [v.voyage_id for v in table.voyages] == ["MV Alpha", "MV Echo", "MV Hotel"]
    errs = {e.line: e for e in table.errors}
    assert sorted(errs) == [4, 5, 7, 9, 10]
    assert "Atlantis Harbour" in errs[4].reason and errs[4].voyage == "MV Bravo"
    assert "RTA must be after the departure" in errs[5].reason
    assert "to" in errs[7].reason and "missing" in errs[7].reason
    assert "no_such_ship" in errs[9].reason
    assert "yesterday" in errs[10].reason
    alpha, echo, hotel = table.voyages
    assert alpha.line == 3 and alpha.request.budget == Budget(float("inf"), 4000)
    assert alpha.request.rta_s - alpha.request.depart_s == 13 * 86400
    assert echo.request.ship == "vlcc_270k" and echo.request.budget.wall_s == 90.0
    assert hotel.request.via == ("Honolulu",)
    assert hotel.request.via_rta_s == (to_posix_s("2026-03-09T00:00Z"),)


def test_missing_column_is_a_file_error(tmp_path):
    f = tmp_path / "fleet.csv"
    f.write_text("vessel,from,depart,rta\nA,Busan,2026-03-03T18:00Z,13d\n")
    with pytest.raises(VoyageFileError, match=r"missing column.*to"):
        read_voyages(f)


def test_candidates_from_depart_and_window(tmp_path):
    f = tmp_path / "fleet.yaml"
    f.write_text(
        "voyages:\n"
        "  - vessel: MV Alpha\n"
        "    from: Busan\n"
        "    to: Long Beach\n"
        "    depart: 2026-03-03T00:00Z/2026-03-04T00:00Z/12h\n"
        "    window: 2026-03-16T00:00Z/2026-03-17T00:00Z/24h\n"
        "  - vessel: MV Bravo\n"  # line 7
        "    from: Busan\n"
        "    to: Long Beach\n"
        "    depart: 2026-03-03T00:00Z\n"
        "    window: 2026-03-16T00:00Z/2026-03-16T12:00Z\n"
        "  - vessel: MV Bravo\n"  # line 12: rta before departure
        "    from: Busan\n"
        "    to: Long Beach\n"
        "    depart: 2026-03-03T00:00Z\n"
        "    rta: 2026-03-02T00:00Z\n")
    table = read_voyages(f)
    alpha = [v for v in table.voyages if v.group == "MV Alpha"]
    assert len(alpha) == 3 * 2  # 3 departures x 2 RTAs
    assert len({v.voyage_id for v in alpha}) == 6
    assert {v.request.rta_s for v in alpha} == {to_posix_s("2026-03-16T00:00Z"),
                                                to_posix_s("2026-03-17T00:00Z")}
    bravo = [v for v in table.voyages if v.group == "MV Bravo"]
    assert len(bravo) == 1 and bravo[0].line == 7
    assert bravo[0].request.rta_s == to_posix_s("2026-03-16T12:00Z")
    assert bravo[0].window_start_s == to_posix_s("2026-03-16T00:00Z")
    assert [(e.line, e.voyage) for e in table.errors] == [(12, "MV Bravo")]
