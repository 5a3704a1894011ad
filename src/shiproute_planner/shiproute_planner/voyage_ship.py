"""The ship a voyage is planned with: ship file (or spec) + loading condition + performance
model choice, resolved or refused with the reason (shared by the planner, the CLI and the
node's parameter check, so the same words are accepted or refused everywhere)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from .errors import InvalidVoyageError


def loaded_ship(ship: Any, loading: str) -> Any:
    """``ship`` (bundled name, file, spec or a performance model) in the loading condition
    ``loading`` ('' = as given; a condition name of the ship file; 'T_F,T_A' drafts in m)."""
    if not str(loading or "").strip():
        return ship
    from .ship import ShipModelError, ShipSpec
    from .ship.condition import ship_in_condition

    if not isinstance(ship, str | Path | ShipSpec):
        raise InvalidVoyageError("give the loading condition with a ship name/file, not with "
                                 "a performance model")
    try:
        return ship_in_condition(ship, loading)
    except ShipModelError as exc:
        raise InvalidVoyageError(f"loading condition: {exc}") from exc


def model_choice_reason(ship: str, ship_model: str, loading: str) -> str | None:
    """Why ``ship`` in ``loading`` cannot be planned with ``ship_model`` (a model file of
    another ship, an unknown condition, unreadable files), or None when it can."""
    from .errors import PlannerError
    from .learned.select import resolve_model
    from .ship import ShipModelError, load_ship

    try:
        spec = loaded_ship(str(ship).strip(), loading)
        if not hasattr(spec, "condition"):
            spec = load_ship(str(ship).strip())
        resolve_model(spec, ship_model)
    except (PlannerError, ShipModelError) as exc:
        return f"ship {ship!r} / loading {loading!r} / ship_model {ship_model!r}: {exc}"
    return None


def loading_block(spec: Any) -> dict[str, Any]:
    """``{"loading": {...}}`` for the plan's extra: the condition and drafts planned with."""
    cond = getattr(spec, "condition", None)
    if cond is None:
        return {}
    return {"loading": {"condition": cond.name, "draft_fore_m": float(cond.draft_fore_m),
                        "draft_aft_m": float(cond.draft_aft_m),
                        "displacement_t": float(cond.displacement_t)}}
