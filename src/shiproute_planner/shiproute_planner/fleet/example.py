"""The fleet example: voyages made from the world trade lanes (bundled copy of the routing
benchmark's lanes) and North Pacific passages timed inside the bundled scenarios.

Lanes whose ports both lie inside the scenarios' grid (10-62 N, 115-245 E) are planned on
`storm_march`; the others on calm water (`forecast` = calm: the bundled scenarios cover the
North Pacific only, give real forecast files for the rest). Passages depart in the storm
(storm_march, two departure times) or in June (calm_june)."""

from __future__ import annotations

import csv
import io
from datetime import UTC, datetime, timedelta
from pathlib import Path

LANES_FILE = Path(__file__).with_name("data") / "world_lanes.csv"
GRID_LAT_DEG = (10.0, 62.0)  # bundled scenarios' grid
GRID_LON_DEG = (115.0, 245.0)
STORM_DEPART = datetime(2026, 3, 4, 0, tzinfo=UTC)
PASSAGES = (  # North Pacific passages: from, to, RTA days, ship, via
    ("Busan", "Long Beach", 13, "container_4600teu", ""),
    ("Yokohama", "Vancouver", 10, "container_4600teu", ""),
    ("Kaohsiung", "Oakland", 16, "container_348m", ""),
    ("Shanghai", "Busan", 2, "bulk_supramax", ""),
    ("Tokyo", "Honolulu", 9, "container_4600teu", ""),
    ("Vancouver", "Honolulu", 9, "bulk_supramax", ""),
    ("Busan", "Yokohama", 3, "container_4600teu", ""),
    ("Qingdao", "USSEA", 16, "vlcc_270k", ""),
    ("Busan", "Long Beach", 15, "container_348m", "Honolulu"),
    ("Hong Kong", "Yokohama", 5, "bulk_supramax", ""),
)
# lane port names the searoute gazetteer spells otherwise: written as their UN/LOCODE
LOCODES = {"Antwerp": "BEANR", "Gothenburg": "SEGOT"}
COLUMNS = ("voyage", "vessel", "ship", "from", "to", "via", "depart", "rta", "objective",
           "budget", "seed", "forecast")


def _inside(port: str) -> bool:
    from ..geo.ports import lookup_port

    p = lookup_port(port)
    lon = p.lon_deg % 360.0
    return (GRID_LAT_DEG[0] <= p.lat_deg <= GRID_LAT_DEG[1]
            and GRID_LON_DEG[0] <= lon <= GRID_LON_DEG[1])


def example_rows(n: int = 50, budget: str = "3000ev") -> list[dict[str, str]]:
    """`n` voyage rows: the world lanes first, then the passages at three departures."""
    rows = []
    with LANES_FILE.open(newline="") as fh:
        lanes = list(csv.DictReader(fh))
    for k, lane in enumerate(lanes):
        lane = {**lane, "from": LOCODES.get(lane["from"], lane["from"]),
                "to": LOCODES.get(lane["to"], lane["to"])}
        dep = STORM_DEPART + timedelta(hours=6 * (k % 4))
        inside = _inside(lane["from"]) and _inside(lane["to"])
        rows.append({"voyage": lane["name"], "vessel": f"lane{k + 1:02d}", "ship": lane["ship"],
                     "from": lane["from"], "to": lane["to"], "via": "",
                     "depart": dep.strftime("%Y-%m-%dT%H:%MZ"), "rta": f"{lane['rta_days']}d",
                     "objective": "fuel", "budget": budget, "seed": str(k),
                     "forecast": "storm_march" if inside else "calm"})
    departures = ((datetime(2026, 3, 3, 18, tzinfo=UTC), "storm_march"),
                  (datetime(2026, 3, 5, 6, tzinfo=UTC), "storm_march"),
                  (datetime(2026, 6, 4, 0, tzinfo=UTC), "calm_june"))
    k = 0
    while len(rows) < n:
        a, b, days, ship, via = PASSAGES[k % len(PASSAGES)]
        dep, fc = departures[(k // len(PASSAGES)) % len(departures)]
        rows.append({"voyage": f"np{k + 1:02d}", "vessel": f"pac{k % len(PASSAGES) + 1:02d}",
                     "ship": ship, "from": a, "to": b, "via": via,
                     "depart": dep.strftime("%Y-%m-%dT%H:%MZ"), "rta": f"{days}d",
                     "objective": "fuel", "budget": budget, "seed": str(100 + k),
                     "forecast": fc})
        k += 1
    return rows[:n]


def example_csv(n: int = 50, budget: str = "3000ev") -> str:
    """The example voyages file as CSV text."""
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=COLUMNS, lineterminator="\n")
    w.writeheader()
    w.writerows(example_rows(n, budget))
    return buf.getvalue()
