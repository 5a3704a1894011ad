"""Write all files of one plan (RTZ validated against RTZ 1.2, GeoJSON, JSON, optional PNG)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..plan_types import RoutePlan
from .rtz import validate_rtz, write_rtz
from .summary import write_geojson, write_json


def write_plan_files(plan: RoutePlan, out_dir: str | Path, *, stem: str | None = None,
                     forecast: Any = None, png: bool = True) -> dict[str, Path]:
    """Write `<stem>.rtz/.geojson/.json[/.png]` into out_dir (stem defaults to plan_<id>)."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    stem = stem or f"plan_{plan.plan_id}"
    files = {"rtz": write_rtz(plan, out / f"{stem}.rtz")}
    validate_rtz(files["rtz"])
    files["geojson"] = write_geojson(plan, out / f"{stem}.geojson")
    files["json"] = write_json(plan, out / f"{stem}.json")
    if png:
        from .plots import write_png

        files["png"] = write_png(plan, out / f"{stem}.png", forecast)
    return files
