"""AIS NMEA and CSV conversion against tracks written by hand from ITU-R M.1371 field values
(see data/make_sample_nmea.py for the values each sentence encodes)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from ais_replay_helpers import DATA
from shiproute_ais_replay.ais.ais_csv import read_csv
from shiproute_ais_replay.ais.ais_nmea import read_nmea, split_line
from shiproute_ais_replay.ais.aisclean import clean
from shiproute_ais_replay.bag.bagreader import BagReader
from shiproute_ais_replay.bag.shipstate import from_rosbags
from shiproute_ais_replay.cli import main
from shiproute_core.topics import OWN_FIX, SHIP_STATE

T0 = 1_700_000_000


def test_nmea_track_of_own_ship():
    tracks, rejected, notes = clean(read_nmea(DATA / "sample_ais.nmea"))
    by = {t.mmsi: t for t in tracks}
    own = by[211001234]
    assert (own.name, own.imo) == ("SHIPROUTE TEST", 9123456)  # from the 2-part type 5
    assert [s.time_ns // 10**9 - T0 for s in own.states] == [0, 60, 120, 180, 360]
    assert [s.longitude_deg for s in own.states] == pytest.approx(
        [10.0, 10.006, 10.012, 10.018, 10.036], abs=1e-6)  # 1/10000 min resolution
    assert all(s.latitude_deg == pytest.approx(54.5, abs=1e-6) for s in own.states)
    assert [s.draft_fore_m for s in own.states] == pytest.approx([12.3] * 5)
    assert math.isnan(own.states[3].heading_deg)  # heading 511 = not available
    assert math.isnan(own.states[4].sog_kn)  # SOG 102.3 = not available
    assert own.states[0].sog_kn == pytest.approx(12.5)
    assert own.states[0].cog_deg == pytest.approx(90.0)
    other = by[366123456]
    assert [s.time_ns // 10**9 - T0 for s in other.states] == [60, 120]  # ISO + unix prefixes
    assert other.states[0].nav_status == 5
    assert rejected == {
        "checksum": 1, "garbage": 1, "no_timestamp": 1, "incomplete_multipart": 1,
        "position_unavailable": 1, "implied_speed": 1,
    }
    assert notes["heading_unavailable"] == 3 and notes["sog_unavailable"] == 1


def test_csv_track_with_bad_rows():
    tracks, rejected, notes = clean(read_csv(DATA / "sample_ais.csv"))
    by = {t.mmsi: t for t in tracks}
    ship = by[538001234]
    assert (ship.name, ship.imo) == ("PACIFIC TEST", 9876543)
    t0 = 1_709_251_200  # 2024-03-01T00:00:00Z
    assert [s.time_ns // 10**9 - t0 for s in ship.states] == [0, 60, 120, 360]  # sorted
    assert [s.longitude_deg for s in ship.states] == [-118.24, -118.237, -118.234, -118.222]
    assert ship.states[0].draft_aft_m == 10.5
    assert math.isnan(ship.states[1].heading_deg)
    assert math.isnan(ship.states[3].sog_kn) and math.isnan(ship.states[3].cog_deg)
    assert len(by[367000001].states) == 2
    assert rejected == {"bad_time": 1, "bad_number": 1, "duplicate_time": 1,
                        "position_unavailable": 1, "position_out_of_range": 1,
                        "implied_speed": 1}
    assert notes == {"heading_unavailable": 3, "cog_unavailable": 2, "sog_unavailable": 1}


def test_implied_speed_threshold_is_50_kn():
    # 0.006 deg of longitude at 54.5 N in 60 s: 0.006 * 60 * cos(54.5 deg) NM / (1/60 h)
    speed_kn = 0.006 * 60 * math.cos(math.radians(54.5)) * 60
    assert speed_kn == pytest.approx(12.54, abs=0.01)
    data = read_nmea(DATA / "sample_ais.nmea")
    _tracks, rejected, _ = clean(data, max_speed_kn=12.0)
    assert rejected["implied_speed"] > 1


def test_tag_block_and_prefix_times():
    assert split_line("\\c:1700000000*5F\\!AIVDO,1,1,,A,x,0*00")[0] == T0 * 10**9
    assert split_line("\\c:1700000000*00\\!AIVDO,1,1,,A,x,0*00")[2] == "tag_block_checksum"
    assert split_line("2023-11-14T22:13:20Z !AIVDM,x")[0] == T0 * 10**9
    assert split_line("1700000000.5;!AIVDM,x")[0] == T0 * 10**9 + 500_000_000


def test_from_ais_cli_writes_own_ship_bag(tmp_path: Path, capsys):
    out = tmp_path / "own"
    assert main(["from-ais", str(DATA / "sample_ais.nmea"), str(out), "--mmsi", "211001234"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["rejected"]["checksum"] == 1
    assert report["messages_written"] == {SHIP_STATE: 5, OWN_FIX: 5}
    reader = BagReader(out)
    states = [from_rosbags(reader.deserialize(m)) for m in reader.messages()
              if m.topic == SHIP_STATE]
    assert [s.longitude_deg for s in states] == pytest.approx(
        [10.0, 10.006, 10.012, 10.018, 10.036], abs=1e-6)


def test_from_ais_cli_all_vessels_get_own_topics(tmp_path: Path, capsys):
    out = tmp_path / "all"
    assert main(["from-ais", str(DATA / "sample_ais.csv"), str(out), "--no-fix"]) == 0
    names = {t.name: t.count for t in BagReader(out).topics()}
    assert names == {"/ais/mmsi_367000001/ship_state": 2, "/ais/mmsi_538001234/ship_state": 4}
