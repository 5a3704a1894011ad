"""Read MarineCadastre-style AIS CSV tracks (MMSI, BaseDateTime, LAT, LON, SOG, COG, Heading,
VesselName, IMO, Status, Draft, ...). Column names are matched case-insensitively; rows that
cannot be parsed are counted by reason."""

from __future__ import annotations

import csv
from pathlib import Path

from ..errors import AisInputError
from .ais_nmea import parse_time_ns
from .aistypes import NAN, AisFix, AisInput, AisStatic

REQUIRED = ("mmsi", "basedatetime", "lat", "lon")
_STATUS_WORDS = {
    "under way using engine": 0, "at anchor": 1, "not under command": 2,
    "restricted maneuverability": 3, "constrained by her draught": 4, "moored": 5,
    "aground": 6, "engaged in fishing": 7, "under way sailing": 8,
}


def _num(row: dict[str, str], key: str, missing: float) -> float:
    text = (row.get(key) or "").strip()
    return float(text) if text else missing


def _status(text: str) -> int:
    text = (text or "").strip().lower()
    if not text:
        return 15
    if text.isdigit():
        return int(text)
    return _STATUS_WORDS.get(text, 15)


def _imo(text: str) -> int:
    digits = "".join(ch for ch in (text or "") if ch.isdigit())
    return int(digits) if digits else 0


def read_csv(path: str | Path) -> AisInput:
    """Parse every row into an AisFix (and an AisStatic when name/IMO/draft are present)."""
    path = Path(path)
    out = AisInput()
    try:
        with path.open(newline="", encoding="utf-8", errors="replace") as f:
            reader = csv.DictReader(f)
            names = {n.strip().lower(): n for n in (reader.fieldnames or [])}
            missing = [c for c in REQUIRED if c not in names]
            if missing:
                raise AisInputError(f"AIS CSV {path} lacks required columns {missing}")
            for raw in reader:
                row = {k.strip().lower(): v for k, v in raw.items() if k is not None}
                _row(out, row)
    except OSError as exc:
        raise AisInputError(f"cannot read AIS CSV {path}: {exc}") from exc
    return out


def _row(out: AisInput, row: dict[str, str]) -> None:
    time_ns = parse_time_ns(row.get("basedatetime") or "")
    if time_ns is None:
        out.rejected["bad_time"] += 1
        return
    try:
        mmsi = int(float(row["mmsi"]))
        fix = AisFix(
            mmsi=mmsi,
            time_ns=time_ns,
            lat_deg=_num(row, "lat", 91.0),
            lon_deg=_num(row, "lon", 181.0),
            sog_kn=_num(row, "sog", 102.3),
            cog_deg=_num(row, "cog", 360.0),
            heading_deg=_num(row, "heading", 511.0),
            nav_status=_status(row.get("status", "")),
        )
        draught = _num(row, "draft", NAN)
    except (ValueError, TypeError):
        out.rejected["bad_number"] += 1
        return
    out.fixes.append(fix)
    name = (row.get("vesselname") or "").strip()
    imo = _imo(row.get("imo", ""))
    if name or imo or draught == draught:
        out.statics.append(AisStatic(mmsi, time_ns, draught if draught > 0 else NAN, name, imo))
