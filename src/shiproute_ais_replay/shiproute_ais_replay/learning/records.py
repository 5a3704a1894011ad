"""Voyage records in: ShipState bags and CSV sensor logs, and the met along the track.

CSV sensor logs (one row per sample, comma-separated, a header row) name each column by its
quantity and unit; a column whose unit is not stated or not known is an error, never a guess:

| quantity | accepted columns (unit) |
|---|---|
| time (UTC) | ``time_utc`` (ISO 8601) or ``time_s`` (POSIX seconds) |
| position | ``latitude_deg``, ``longitude_deg`` |
| speed over ground | ``sog_kn`` or ``sog_m_s`` |
| course over ground, heading | ``cog_deg``, ``heading_deg`` (true) |
| speed through water (log) | ``stw_kn`` or ``stw_m_s`` (optional: else SOG minus current) |
| shaft speed | ``shaft_rpm`` or ``shaft_speed_rps`` |
| fuel rate, main engine | ``fuel_rate_t_per_h``, ``fuel_rate_kg_per_h``, ``fuel_rate_t_per_day`` |
| drafts | ``draft_fore_m``, ``draft_aft_m`` |
| optional | ``rudder_angle_deg``, ``water_depth_m``, ``voyage`` (integer id) |

Bags: ShipState messages on the ship-state topic (shiproute_core.topics.SHIP_STATE; the fields
above, rudder and depth unknown).
Voyages: the ``voyage`` column, else one per input file, split where the records pause > 6 h.
"""

from __future__ import annotations

import csv
import math
from collections.abc import Sequence
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path

import numpy as np
from shiproute_core.units import M_S_PER_KNOT

from ..errors import AisReplayError

VOYAGE_GAP_S = 6 * 3600.0
COLUMNS = ("time_s", "latitude_deg", "longitude_deg", "sog_kn", "cog_deg", "heading_deg",
           "stw_kn", "shaft_rpm", "fuel_rate_t_per_h", "draft_fore_m", "draft_aft_m",
           "rudder_angle_deg", "water_depth_m", "voyage")
# quantity prefix -> {column name: factor to the canonical unit}
_UNITS: dict[str, dict[str, float]] = {
    "time": {"time_utc": 1.0, "time_s": 1.0},
    "latitude": {"latitude_deg": 1.0}, "longitude": {"longitude_deg": 1.0},
    "sog": {"sog_kn": 1.0, "sog_m_s": 1.0 / M_S_PER_KNOT},
    "cog": {"cog_deg": 1.0}, "heading": {"heading_deg": 1.0},
    "stw": {"stw_kn": 1.0, "stw_m_s": 1.0 / M_S_PER_KNOT},
    "shaft": {"shaft_rpm": 1.0, "shaft_speed_rps": 60.0},
    "fuel": {"fuel_rate_t_per_h": 1.0, "fuel_rate_kg_per_h": 1e-3, "fuel_rate_t_per_day": 1 / 24},
    "draft_fore": {"draft_fore_m": 1.0}, "draft_aft": {"draft_aft_m": 1.0},
    "rudder": {"rudder_angle_deg": 1.0}, "water_depth": {"water_depth_m": 1.0},
    "voyage": {"voyage": 1.0},
}
_CANONICAL = {"time": "time_s", "sog": "sog_kn", "stw": "stw_kn", "shaft": "shaft_rpm",
              "fuel": "fuel_rate_t_per_h"}
_REQUIRED = ("time", "latitude", "longitude", "sog", "cog", "heading", "shaft", "fuel",
             "draft_fore", "draft_aft")


class RecordsError(AisReplayError):
    """Records cannot be read: missing columns, units not stated, unreadable file."""


@dataclass(frozen=True)
class Records:
    """Column arrays (``COLUMNS``, NaN = unknown) of all records, in time order."""

    columns: dict[str, np.ndarray]
    sources: tuple[str, ...]

    def __len__(self) -> int:
        return int(self.columns["time_s"].size)


def _quantity(name: str) -> str | None:
    for q in sorted(_UNITS, key=len, reverse=True):
        if name == q or name.startswith(q + "_"):
            return q
    return None


def read_csv(path: str | Path) -> dict[str, np.ndarray]:
    """Columns of one CSV sensor log (see the module docstring), canonical units."""
    path = Path(path)
    try:
        with path.open(newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))
    except (OSError, UnicodeDecodeError) as exc:
        raise RecordsError(f"{path}: cannot read CSV records: {exc}") from exc
    if len(rows) < 2:
        raise RecordsError(f"{path}: no records (a header row and data rows are needed)")
    header = [h.strip().lower() for h in rows[0]]
    found: dict[str, tuple[int, str]] = {}
    for i, name in enumerate(header):
        q = _quantity(name)
        if q is None:
            continue  # other columns (e.g. notes) are ignored
        if name not in _UNITS[q]:
            raise RecordsError(
                f"{path}: column '{name}' does not state a known unit; use one of "
                f"{', '.join(_UNITS[q])}")
        found[q] = (i, name)
    missing = [q for q in _REQUIRED if q not in found]
    if missing:
        need = "; ".join(f"{q}: {' or '.join(_UNITS[q])}" for q in missing)
        raise RecordsError(f"{path}: records lack required columns ({need})")
    n = len(rows) - 1
    cols = {c: np.full(n, np.nan) for c in COLUMNS}
    for q, (i, name) in found.items():
        target = _CANONICAL.get(q, name)
        values = [r[i].strip() if i < len(r) else "" for r in rows[1:]]
        if name == "time_utc":
            cols[target] = np.array([_iso_s(v) for v in values])
        else:
            cols[target] = np.array([_num(v) for v in values]) * _UNITS[q][name]
    return cols


def _num(text: str) -> float:
    try:
        return float(text) if text else math.nan
    except ValueError:
        return math.nan


def _iso_s(text: str) -> float:
    try:
        t = datetime.fromisoformat(text.replace("Z", "+00:00"))
    except ValueError:
        return math.nan
    return (t if t.tzinfo else t.replace(tzinfo=UTC)).timestamp()


def read_bag(path: str | Path) -> dict[str, np.ndarray]:
    """Columns of the ShipState messages of one bag (streamed)."""
    from shiproute_core.topics import SHIP_STATE as OWN_STATE_TOPIC

    from ..bag.bagreader import BagReader
    from ..bag.shipstate import from_rosbags

    reader = BagReader(path)
    out: dict[str, list[float]] = {c: [] for c in COLUMNS}
    for msg in reader.messages():
        if msg.topic != OWN_STATE_TOPIC or not reader.is_known(msg):
            continue
        rec = from_rosbags(reader.deserialize(msg))
        out["time_s"].append(rec.time_ns / 1e9)
        for c in COLUMNS[1:11]:  # ShipState field names = column names
            out[c].append(float(getattr(rec, c)))
        for c in COLUMNS[11:]:
            out[c].append(math.nan)
    if not out["time_s"]:
        raise RecordsError(f"{path}: no ShipState messages on {OWN_STATE_TOPIC}")
    return {c: np.array(v, dtype=float) for c, v in out.items()}


def read_records(paths: Sequence[str | Path]) -> Records:
    """All records of bags (directory or .mcap) and CSV logs, voyages numbered, time-sorted."""
    if not paths:
        raise RecordsError("no records given")
    parts, next_voyage = [], 0
    for p in paths:
        p = Path(p)
        if not p.exists():
            raise RecordsError(f"records {p} do not exist")
        cols = read_csv(p) if p.suffix.lower() == ".csv" else read_bag(p)
        order = np.argsort(cols["time_s"], kind="stable")
        cols = {k: v[order] for k, v in cols.items()}
        if np.all(np.isnan(cols["voyage"])):
            gap = np.concatenate([[0], np.diff(cols["time_s"]) > VOYAGE_GAP_S])
            cols["voyage"] = next_voyage + np.cumsum(gap).astype(float)
        else:
            cols["voyage"] = next_voyage + cols["voyage"] - np.nanmin(cols["voyage"])
        next_voyage = int(np.nanmax(cols["voyage"])) + 1
        parts.append(cols)
    merged = {c: np.concatenate([q[c] for q in parts]) for c in COLUMNS}
    order = np.argsort(merged["time_s"], kind="stable")
    return Records({c: v[order] for c, v in merged.items()}, tuple(str(p) for p in paths))


def join_met(records: Records, forecasts: Sequence) -> dict[str, np.ndarray]:
    """Met along the track (wind, wind sea, swell, current; `SeaState` names) from canonical
    forecast datasets; a later dataset overrides earlier ones where it covers the time.
    Records outside every dataset's time span get NaN (the cleaning drops them)."""
    from shiproute_planner.learned.features import SEA_COLUMNS
    from shiproute_planner.ship import SeaState
    from shiproute_weather.sampling.sampler import ForecastSampler

    c = records.columns
    out = {k: np.full(len(records), np.nan) for k in SEA_COLUMNS}
    for ds in forecasts:
        times = ds["time"].values.astype("datetime64[s]").astype(float)
        inside = (c["time_s"] >= times.min()) & (c["time_s"] <= times.max())
        inside &= np.isfinite(c["latitude_deg"]) & np.isfinite(c["longitude_deg"])
        if not np.any(inside):
            continue
        sample = ForecastSampler(ds).sample(c["longitude_deg"][inside],
                                            c["latitude_deg"][inside], c["time_s"][inside])
        sea = SeaState.from_forecast(sample)
        for k in SEA_COLUMNS:
            out[k][inside] = np.broadcast_to(getattr(sea, k), (int(inside.sum()),))
    return out
