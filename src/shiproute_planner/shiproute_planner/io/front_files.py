"""The time-fuel front as files: JSON (points with each plan's summary), GeoJSON (one route
per point) and a PNG (fuel vs ETA, feasible and flagged points apart)."""

from __future__ import annotations

import json
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from ..errors import OutputError
from ..front import TimeFuelFront
from .summary import plan_geojson, plan_summary


def _iso(t_s: float) -> str:
    return datetime.fromtimestamp(t_s, UTC).strftime("%Y-%m-%dT%H:%M:%SZ")


def front_points(front: TimeFuelFront) -> list[dict[str, Any]]:
    """One row per plan: ETA, voyage hours, fuel, distance, feasibility, CO2/cost if known."""
    rows = []
    for k, p in enumerate(front.plans):
        goal = p.extra.get("objective") or {}
        rows.append({"point": k, "plan_id": p.plan_id, "objective": p.objective,
                     "eta": _iso(p.eta_s), "eta_s": p.eta_s,
                     "voyage_h": (p.eta_s - p.departure_s) / 3600.0,
                     "fuel_t": p.total_fuel_t, "distance_nm": p.total_distance_nm,
                     "mean_sog_kn": p.total_distance_nm / max(p.total_time_s / 3600.0, 1e-9),
                     "feasible": p.feasible, "infeasible_reasons": list(p.infeasible_reasons),
                     **({"co2_t": goal["co2_t"]} if "co2_t" in goal else {})})
    return rows


def front_summary(front: TimeFuelFront) -> dict[str, Any]:
    """The whole front: voyage, ends, points, notes and every plan's own summary."""
    first = front.plans[0]
    return {"ports": list(first.ports), "departure": _iso(first.departure_s),
            "earliest_safe_arrival": _iso(front.earliest_eta_s),
            "latest_arrival": _iso(front.latest_arrival_s), "monotone": front.monotone,
            "compute_time_s": front.compute_time_s, "points": front_points(front),
            "notes": list(front.notes), "plans": [plan_summary(p) for p in front.plans]}


def front_geojson(front: TimeFuelFront) -> dict[str, Any]:
    """FeatureCollection with every plan's legs, tagged with the point index and its ETA."""
    feats = []
    for k, p in enumerate(front.plans):
        for f in plan_geojson(p)["features"]:
            f["properties"].update(front_point=k, plan_id=p.plan_id, plan_eta=_iso(p.eta_s),
                                   plan_fuel_t=p.total_fuel_t, plan_feasible=p.feasible)
            feats.append(f)
    return {"type": "FeatureCollection", "properties": {"points": front_points(front)},
            "features": feats}


def _write(path: Path, data: dict[str, Any]) -> Path:
    try:
        path.write_text(json.dumps(data, indent=1, default=float, allow_nan=False))
    except (OSError, ValueError) as exc:
        raise OutputError(f"cannot write {path}: {exc}") from exc
    return path


def write_front_json(front: TimeFuelFront, path: str | Path) -> Path:
    """Write `front_summary` as JSON."""
    return _write(Path(path), _finite(front_summary(front)))


def write_front_geojson(front: TimeFuelFront, path: str | Path) -> Path:
    """Write `front_geojson`."""
    return _write(Path(path), _finite(front_geojson(front)))


def _finite(x: Any) -> Any:
    """NaN/inf -> None, recursively (JSON has no NaN)."""
    if isinstance(x, float):
        return x if x == x and abs(x) != float("inf") else None
    if isinstance(x, dict):
        return {k: _finite(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [_finite(v) for v in x]
    return x


def write_front_png(front: TimeFuelFront, path: str | Path) -> Path:
    """Fuel [t] vs voyage time [h]: the front as a line, flagged plans marked with x."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = front_points(front)
    fig, ax = plt.subplots(figsize=(7.5, 5))
    h = [r["voyage_h"] for r in rows]
    f = [r["fuel_t"] for r in rows]
    ax.plot(h, f, "-", color="0.6", zorder=1)
    ok = [r for r in rows if r["feasible"]]
    bad = [r for r in rows if not r["feasible"]]
    ax.scatter([r["voyage_h"] for r in ok], [r["fuel_t"] for r in ok], c="tab:blue",
               label="feasible", zorder=2)
    if bad:
        ax.scatter([r["voyage_h"] for r in bad], [r["fuel_t"] for r in bad], c="tab:red",
                   marker="x", label="flagged (infeasible)", zorder=3)
    latest_h = (front.latest_arrival_s - front.plans[0].departure_s) / 3600.0
    ax.axvline(latest_h, color="k", ls="--", lw=1, label="latest arrival (RTA)")
    ax.set_xlabel("voyage time [h]")
    ax.set_ylabel("fuel [t]")
    ax.set_title("time-fuel front: " + " -> ".join(front.plans[0].ports))
    ax.grid(alpha=0.3)
    ax.legend()
    try:
        fig.savefig(path, dpi=110, bbox_inches="tight")
    except OSError as exc:
        raise OutputError(f"cannot write {path}: {exc}") from exc
    finally:
        plt.close(fig)
    return Path(path)
