"""The loading condition a voyage is planned in: a named condition of the ship file ("design",
"ballast", ...) or explicit drafts "T_F,T_A" [m] (fore, aft), which change resistance, wave
added resistance, seakeeping, squat and the under-keel clearance through the ship's drafts."""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path

from .errors import LoadingConditionError
from .loading import load_ship
from .spec import ShipSpec

_DRAFTS = re.compile(r"^\s*([0-9]+(?:\.[0-9]*)?)\s*,\s*([0-9]+(?:\.[0-9]*)?)\s*$")
RHO_SEA_T_M3 = 1.025


def at_drafts(ship: ShipSpec, draft_fore_m: float, draft_aft_m: float) -> ShipSpec:
    """``ship`` floating at other drafts: displacement changed by the waterplane times the
    mean-draft change (parallel sinkage), everything else as in the file."""
    c = ship.condition
    if draft_fore_m == c.draft_fore_m and draft_aft_m == c.draft_aft_m:
        return ship
    d_mean = 0.5 * (draft_fore_m + draft_aft_m) - ship.mean_draft_m
    h = ship.hull
    extra_t = RHO_SEA_T_M3 * h.waterplane_coefficient * h.lwl_m * h.breadth_m * d_mean
    cond = dataclasses.replace(c, name=f"{c.name} at {draft_fore_m:.2f}/{draft_aft_m:.2f} m",
                               draft_fore_m=float(draft_fore_m), draft_aft_m=float(draft_aft_m),
                               displacement_t=c.displacement_t + extra_t)
    return dataclasses.replace(ship, condition=cond, content_hash=ship.content_hash
                               + f"#drafts={draft_fore_m:.3f}/{draft_aft_m:.3f}")


def parse_loading(text: str) -> tuple[str, tuple[float, float] | None]:
    """'' (the file's default), a condition name, or 'T_F,T_A' drafts -> (name, drafts)."""
    text = str(text or "").strip()
    m = _DRAFTS.match(text)
    if m:
        return "", (float(m.group(1)), float(m.group(2)))
    if "," in text or (text and not re.match(r"^[A-Za-z_][\w-]*$", text)):
        raise LoadingConditionError(
            f"loading {text!r}: use a condition of the ship file (e.g. design, ballast) or "
            "drafts fore,aft in metres (e.g. 11.5,12.5)")
    return text, None


def ship_in_condition(ship: str | Path | ShipSpec, loading: str) -> ShipSpec:
    """The ship (bundled name, file or spec) in the loading condition ``loading``; explicit
    drafts start from the file's condition nearest in mean draft (its GM and bulb area)."""
    name, drafts = parse_loading(loading)
    if isinstance(ship, ShipSpec):
        if name and name != ship.condition.name:
            raise LoadingConditionError(
                f"loading {name!r}: give the ship by name or file to change its condition")
        base = ship
    else:
        base = load_ship(ship, name or None) if name else load_ship(ship)
        if name and name not in base.conditions:  # load_ship already refuses; kept explicit
            raise LoadingConditionError(f"ship {base.name} has no loading condition {name!r}")
    if drafts is None:
        return base
    fore, aft = drafts
    if not min(fore, aft) >= 0.5 or max(fore, aft) >= base.hull.depth_m:
        raise LoadingConditionError(
            f"loading drafts {fore:g},{aft:g} m: each must be 0.5 m or more and below the "
            f"hull depth {base.hull.depth_m:g} m of {base.name}")
    if abs(fore - aft) > 0.03 * base.hull.lpp_m:
        raise LoadingConditionError(
            f"loading drafts {fore:g},{aft:g} m: trim {aft - fore:+.1f} m exceeds 3 % of Lpp "
            f"({0.03 * base.hull.lpp_m:.1f} m)")
    if not isinstance(ship, ShipSpec):
        mean = 0.5 * (fore + aft)
        nearest = min(base.conditions, key=lambda c: abs(
            load_ship(ship, c).mean_draft_m - mean))
        base = load_ship(ship, nearest)
    out = at_drafts(base, fore, aft)
    h, c = out.hull, out.condition
    cb = c.displacement_t / RHO_SEA_T_M3 / (h.lwl_m * h.breadth_m * 0.5 * (fore + aft))
    if not 0.35 < cb < 0.92 or c.displacement_t <= 0:
        raise LoadingConditionError(
            f"loading drafts {fore:g},{aft:g} m give block coefficient {cb:.3f} (outside "
            f"0.35-0.92) for {base.name}: not a condition this hull floats in")
    return out
