"""Voyages file (CSV or YAML) -> voyage specs, one per voyage x candidate time, and the rows
that cannot be planned with their line number and reason (they are skipped, the rest plan).

Columns (case-insensitive): `vessel`, `from`, `to`, `depart` and `rta` or `window` are
required; `voyage`, `ship`, `via` (`PORT[@TIME];...`), `objective`, `model`, `method`,
`budget` (`3s` or `4000ev`), `seed`, `stage_hours` and `forecast` are optional. `depart` may be
`START/END/STEP` (candidate departures); `window` is `EARLIEST/LATEST` (RTA = LATEST) or
`EARLIEST/LATEST/STEP` (candidate RTAs from EARLIEST to LATEST).
"""

from __future__ import annotations

import csv
import re
from dataclasses import dataclass, field
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from ..errors import PlannerError
from ..plan_request import PlanRequest, build_request, duration_s, parse_time_s
from .errors import VoyageFileError

REQUIRED = ("vessel", "from", "to", "depart")
OPTIONAL = ("voyage", "rta", "window", "ship", "via", "objective", "model", "method", "budget",
            "seed", "stage_hours", "forecast")
MAX_CANDIDATES = 64  # per row: a typo in STEP must not make a million voyages


@dataclass(frozen=True)
class RowError:
    """A row that is skipped: where it is and why."""

    line: int
    voyage: str
    reason: str


@dataclass(frozen=True)
class VoyageSpec:
    """One voyage to plan: its id (unique in the file), the row it came from, the request and
    the forecast it names (None: every forecast given)."""

    voyage_id: str
    vessel: str
    line: int
    request: PlanRequest
    forecast: str | None = None
    group: str = ""  # the row's voyage id: candidates of one row share it
    window_start_s: float | None = None  # earliest arrival of a window (None: RTA only)
    extra: dict[str, str] = field(default_factory=dict, compare=False, hash=False)


@dataclass(frozen=True)
class VoyageTable:
    """What a voyages file yields: the voyages to plan and the rows skipped."""

    voyages: tuple[VoyageSpec, ...]
    errors: tuple[RowError, ...]


def read_voyages(path: str | Path, *, default_budget: str = "3s",
                 default_ship: str = "container_4600teu") -> VoyageTable:
    """Read a CSV or YAML voyages file; a bad row becomes a RowError, never an exception."""
    p = Path(path)
    if not p.is_file():
        raise VoyageFileError(f"voyages file {p} does not exist")
    if p.suffix.lower() in (".yaml", ".yml"):
        rows = _yaml_rows(p)
    elif p.suffix.lower() in (".csv", ".txt"):
        rows = _csv_rows(p)
    else:
        raise VoyageFileError(f"voyages file {p}: use .csv or .yaml, not {p.suffix!r}")
    return voyages_from_rows(rows, str(p), default_budget=default_budget,
                             default_ship=default_ship)


def voyages_from_rows(rows: list[tuple[int, dict[str, Any]]], source: str, *,
                      default_budget: str = "3s",
                      default_ship: str = "container_4600teu") -> VoyageTable:
    """(line, row) pairs -> voyages and row errors (ids made unique in file order)."""
    voyages: list[VoyageSpec] = []
    errors: list[RowError] = []
    seen: dict[str, int] = {}
    for line, raw in rows:
        row = {str(k).strip().lower(): ("" if v is None else v) for k, v in raw.items()
               if k is not None}
        base = str(row.get("voyage") or row.get("vessel") or f"line{line}").strip()
        try:
            specs = _row_voyages(line, row, default_budget, default_ship)
        except PlannerError as exc:
            errors.append(RowError(line, base, str(exc)))
            continue
        n = seen.get(base, 0) + 1
        seen[base] = n
        group = base if n == 1 else f"{base}-{n}"
        for spec in specs:
            vid = group if len(specs) == 1 else f"{group}@{spec.voyage_id}"
            voyages.append(VoyageSpec(vid, spec.vessel, line, spec.request, spec.forecast,
                                      group, spec.window_start_s, spec.extra))
    return VoyageTable(tuple(voyages), tuple(errors))


def _row_voyages(line: int, row: dict[str, Any], default_budget: str,
                 default_ship: str) -> list[VoyageSpec]:
    """The voyages of one row (several with candidate departures or RTAs)."""
    missing = [c for c in REQUIRED if not str(row.get(c, "")).strip()]
    if not str(row.get("rta", "")).strip() and not str(row.get("window", "")).strip():
        missing.append("rta or window")
    if missing:
        raise VoyageFileError(f"missing value for column(s) {', '.join(missing)}")
    _check_port(str(row["from"]))
    _check_port(str(row["to"]))
    via = row.get("via", "")
    vias = ([str(v) for v in via] if isinstance(via, list)
            else [v for v in re.split(r"[;|]", str(via)) if v.strip()])
    for v in vias:
        _check_port(v.partition("@")[0])
    ship = str(row.get("ship") or default_ship).strip()
    _check_ship(ship)
    departs = _times(str(row["depart"]), "departure")
    window = str(row.get("window", "")).strip()
    rta_text = str(row.get("rta", "")).strip()
    out = []
    for dep_s in departs:
        if rta_text:
            rtas, start = [rta_text], None
        else:
            parts = window.split("/")
            if len(parts) not in (2, 3):
                raise VoyageFileError(
                    f"window {window!r}: use EARLIEST/LATEST or EARLIEST/LATEST/STEP")
            start = parse_time_s(parts[0], "window start")
            rtas = [_iso(t) for t in _times(window, "window")] if len(parts) == 3 else [parts[1]]
        for rta in rtas:
            req = build_request(
                origin=str(row["from"]), destination=str(row["to"]), depart=_iso(dep_s),
                rta=rta, via=vias, ship=ship, objective=str(row.get("objective") or "fuel"),
                method=str(row.get("method") or "seed_ga"), model=str(row.get("model") or ""),
                budget=str(row.get("budget") or default_budget),
                seed=_int(row.get("seed") or 0, "seed"),
                stage_hours=_float(row.get("stage_hours") or 12.0, "stage_hours"))
            if start is not None and start > req.rta_s:
                raise VoyageFileError(f"window {window!r} ends before it starts")
            tag = _tag(req, len(departs) > 1, len(rtas) > 1)
            out.append(VoyageSpec(tag, str(row["vessel"]).strip(), line, req,
                                  str(row.get("forecast") or "").strip() or None,
                                  window_start_s=start))
    if len(out) > MAX_CANDIDATES:
        raise VoyageFileError(f"{len(out)} candidate voyages in one row: at most "
                              f"{MAX_CANDIDATES} (check the STEP of depart/window)")
    return out


def _tag(req: PlanRequest, by_depart: bool, by_rta: bool) -> str:
    """Candidate label: departure and/or RTA as compact UTC times."""
    parts = []
    if by_depart:
        parts.append("D" + _compact(req.depart_s))
    if by_rta:
        parts.append("A" + _compact(req.rta_s))
    return "_".join(parts)


def _compact(t_s: float) -> str:
    return datetime.fromtimestamp(t_s, UTC).strftime("%m%dT%H%M")


def _iso(t_s: float) -> str:
    return datetime.fromtimestamp(t_s, UTC).strftime("%Y-%m-%dT%H:%M:%SZ")


def _times(text: str, what: str) -> list[float]:
    """'TIME' or 'START/END/STEP' -> POSIX seconds (START, START + STEP, ... <= END);
    'EARLIEST/LATEST' gives LATEST only (an RTA window's deadline)."""
    parts = [p.strip() for p in text.split("/")]
    if len(parts) == 1:
        return [parse_time_s(parts[0], what)]
    if len(parts) == 2:
        return [parse_time_s(parts[1], what)]
    if len(parts) != 3:
        raise VoyageFileError(f"{what} {text!r}: use TIME or START/END/STEP")
    a, b = parse_time_s(parts[0], what), parse_time_s(parts[1], what)
    step = duration_s(parts[2])
    if step <= 0 or b < a:
        raise VoyageFileError(f"{what} {text!r}: END before START or STEP not positive")
    n = int((b - a) / step + 1e-9) + 1
    if n > MAX_CANDIDATES:
        raise VoyageFileError(f"{what} {text!r} gives {n} candidates: at most {MAX_CANDIDATES}")
    return [a + k * step for k in range(n)]


def _check_port(text: str) -> None:
    """Unknown ports fail here, before any worker is asked (gazetteer look-up only)."""
    from ..geo.ports import lookup_port

    if not text.strip():
        raise VoyageFileError("empty port name")
    lookup_port(text)


def _check_ship(ship: str) -> None:
    from ..ship import bundled_ships

    if ship in bundled_ships():
        return
    if not Path(ship).is_file():
        raise VoyageFileError(
            f"ship {ship!r} is neither a bundled ship ({', '.join(bundled_ships())}) nor a file")


def _int(v: Any, name: str) -> int:
    try:
        return int(str(v).strip())
    except ValueError:
        raise VoyageFileError(f"{name} {v!r} is not an integer") from None


def _float(v: Any, name: str) -> float:
    try:
        return float(str(v).strip())
    except ValueError:
        raise VoyageFileError(f"{name} {v!r} is not a number") from None


def _csv_rows(p: Path) -> list[tuple[int, dict[str, Any]]]:
    """CSV rows with the line each starts on (comment lines '#' and blank lines skipped)."""
    with p.open(newline="", encoding="utf-8-sig") as fh:
        lines = [(n, s) for n, s in enumerate(fh, start=1)
                 if s.strip() and not s.lstrip().startswith("#")]
    if not lines:
        raise VoyageFileError(f"voyages file {p} is empty")
    header = next(csv.reader([lines[0][1]]))
    cols = [h.strip().lower() for h in header]
    _check_columns(p, cols)
    out: list[tuple[int, dict[str, Any]]] = []
    for n, text in lines[1:]:
        values = next(csv.reader([text]))
        row: dict[str, Any] = dict(zip(cols, values, strict=False))
        if len(values) > len(cols):
            row["__extra__"] = values[len(cols):]
        out.append((n, row))
    return out


def _check_columns(p: Path, cols: list[str]) -> None:
    """A header without a required column makes every row unplannable: say so once."""
    missing = [c for c in REQUIRED if c not in cols]
    if "rta" not in cols and "window" not in cols:
        missing.append("rta or window")
    if missing:
        raise VoyageFileError(
            f"voyages file {p}: missing column(s) {', '.join(missing)} (required: "
            f"{', '.join(REQUIRED)} and rta or window; optional: {', '.join(OPTIONAL)})")


def _yaml_rows(p: Path) -> list[tuple[int, dict[str, Any]]]:
    """YAML: a list of mappings, or a mapping with a `voyages` list; line of each mapping."""
    import yaml

    try:
        root = yaml.compose(p.read_text(encoding="utf-8"), Loader=yaml.SafeLoader)
    except yaml.YAMLError as exc:
        raise VoyageFileError(f"voyages file {p} is not valid YAML: {exc}") from None
    node = root
    if isinstance(root, yaml.MappingNode):
        node = next((v for k, v in root.value if k.value == "voyages"), None)
    if not isinstance(node, yaml.SequenceNode):
        raise VoyageFileError(f"voyages file {p}: expected a list of voyages (or 'voyages:')")
    out: list[tuple[int, dict[str, Any]]] = []
    for item in node.value:
        line = item.start_mark.line + 1
        value = yaml.SafeLoader(yaml.serialize(item)).get_single_data()
        if not isinstance(value, dict):
            out.append((line, {}))
            continue
        out.append((line, {str(k): v for k, v in value.items()}))
    cols = sorted({str(k).strip().lower() for _, r in out for k in r})
    _check_columns(p, cols)
    return out
