"""Read and validate YAML ship files into ``ShipSpec`` (errors name file, key and problem)."""

from __future__ import annotations

import functools
import hashlib
from collections.abc import Mapping
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from .errors import ShipFileError, UnknownShipError
from .fuel import parse_economics
from .spec import (
    EngineSpec,
    HullSpec,
    LoadingCondition,
    PropellerSpec,
    SeakeepingSpec,
    ShipSpec,
    WaterSpec,
    WindageSpec,
)
from .wind import TABLE_ANGLES_DEG, blendermann_caa, coefficient_sets

SHIP_TYPES = ("container", "tanker", "bulk", "general")


def bundled_ships() -> list[str]:
    """Names of the ship files shipped in ``shiproute_planner/ships``."""
    root = resources.files("shiproute_planner") / "ships"
    return sorted(p.name[:-5] for p in root.iterdir() if p.name.endswith(".yaml"))


def ship_file_path(name_or_path: str | Path) -> Path:
    """Resolve a bundled ship name or a file path to an existing YAML file."""
    p = Path(name_or_path)
    if p.suffix in (".yaml", ".yml") and p.is_file():
        return p
    bundled = resources.files("shiproute_planner") / "ships" / f"{name_or_path}.yaml"
    if bundled.is_file():
        return Path(str(bundled))
    raise UnknownShipError(
        f"ship '{name_or_path}' is neither a YAML file nor a bundled ship "
        f"(bundled: {', '.join(bundled_ships())})"
    )


def load_ship(name_or_path: str | Path, condition: str | None = None) -> ShipSpec:
    """Load, validate and resolve a ship file for one loading condition (default: the file's)."""
    path = ship_file_path(name_or_path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise ShipFileError(str(path), "", f"cannot read file: {exc}") from exc
    return _parse_cached(text, str(path), condition)


@functools.lru_cache(maxsize=16)
def _parse_cached(text: str, source: str, condition: str | None) -> ShipSpec:
    """`parse_ship` memoised on the file's text: a re-planning node reads its ship file on
    every plan (edits take effect) but parses it once (the specs are frozen)."""
    return parse_ship(text, source, condition)


def parse_ship(text: str, source: str, condition: str | None = None) -> ShipSpec:
    """Parse ship-file YAML text; ``source`` names the file in error messages."""
    try:
        doc = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        raise ShipFileError(source, "", f"invalid YAML: {exc}") from exc
    r = _Reader(source)
    root = r.section(doc, "")
    hull_m = r.section(root.get("hull"), "hull")
    prop_m = r.section(root.get("propeller"), "propeller")
    eng_m = r.section(root.get("engine"), "engine")
    wind_m = r.section(root.get("windage"), "windage")
    conds_m = r.section(root.get("loading_conditions"), "loading_conditions")
    sk_m = r.section(root.get("seakeeping", {}), "seakeeping")
    water_m = r.section(root.get("water", {}), "water")

    name = r.text(root, "name", "")
    ship_type = r.text(root, "type", "")
    if ship_type not in SHIP_TYPES:
        raise ShipFileError(source, "type", f"must be one of {SHIP_TYPES}, got '{ship_type}'")
    hull = HullSpec(
        lpp_m=r.num(hull_m, "lpp_m", "hull", 20, 500),
        lwl_m=r.num(hull_m, "lwl_m", "hull", 20, 520),
        breadth_m=r.num(hull_m, "breadth_m", "hull", 3, 80),
        depth_m=r.num(hull_m, "depth_m", "hull", 2, 50),
        midship_coefficient=r.num(hull_m, "midship_coefficient", "hull", 0.7, 1.0),
        waterplane_coefficient=r.num(hull_m, "waterplane_coefficient", "hull", 0.5, 1.0),
        lcb_percent=r.num(hull_m, "lcb_percent", "hull", -6, 6),
        stern_shape_coefficient=r.num(hull_m, "stern_shape_coefficient", "hull", -25, 10),
        bulb_area_m2=r.num(hull_m, "bulb_area_m2", "hull", 0, 200, default=0.0),
        bulb_center_height_m=r.num(hull_m, "bulb_center_height_m", "hull", 0, 20, default=0.0),
        transom_area_m2=r.num(hull_m, "transom_area_m2", "hull", 0, 300, default=0.0),
        appendage_area_m2=r.num(hull_m, "appendage_area_m2", "hull", 0, 1000, default=0.0),
        appendage_form_factor=r.num(hull_m, "appendage_form_factor", "hull", 1, 4, default=1.5),
        wetted_surface_m2=r.opt_num(hull_m, "wetted_surface_m2", "hull", 100, 60000),
        pitch_gyradius_ratio=r.num(hull_m, "pitch_gyradius_ratio", "hull", 0.15, 0.35, 0.25),
        bow_height_m=r.num(hull_m, "bow_height_m", "hull", 2, 60),
    )
    propeller = PropellerSpec(
        blades=int(r.num(prop_m, "blades", "propeller", 2, 7)),
        diameter_m=r.num(prop_m, "diameter_m", "propeller", 0.5, 15),
        pitch_ratio=r.num(prop_m, "pitch_ratio", "propeller", 0.5, 1.4),
        area_ratio=r.num(prop_m, "area_ratio", "propeller", 0.3, 1.05),
        shaft_center_height_m=r.num(prop_m, "shaft_center_height_m", "propeller", 0.3, 12),
        shaft_efficiency=r.num(prop_m, "shaft_efficiency", "propeller", 0.9, 1.0, 0.99),
    )
    if propeller.blades != prop_m["blades"]:
        raise ShipFileError(source, "propeller.blades", "must be a whole number")
    loads = r.num_list(eng_m, "sfoc_load_fraction", "engine", 0.0, 1.5)
    sfocs = r.num_list(eng_m, "sfoc_g_per_kwh", "engine", 100, 400)
    if len(loads) != len(sfocs) or len(loads) < 2 or np.any(np.diff(loads) <= 0):
        raise ShipFileError(
            source,
            "engine.sfoc_load_fraction",
            "needs >= 2 strictly increasing loads, as many as engine.sfoc_g_per_kwh values",
        )
    engine = EngineSpec(
        mcr_kw=r.num(eng_m, "mcr_kw", "engine", 100, 150000),
        rpm_mcr=r.num(eng_m, "rpm_mcr", "engine", 30, 1000),
        rpm_min=r.num(eng_m, "rpm_min", "engine", 5, 1000),
        rpm_max=r.num(eng_m, "rpm_max", "engine", 10, 1100),
        overload_power_fraction=r.num(eng_m, "overload_power_fraction", "engine", 0.5, 1.2, 1.0),
        torque_limit_fraction=r.num(eng_m, "torque_limit_fraction", "engine", 0.5, 1.3, 1.0),
        sfoc_load_fraction=tuple(loads),
        sfoc_g_per_kwh=tuple(sfocs),
    )
    if not engine.rpm_min < engine.rpm_mcr <= engine.rpm_max:
        raise ShipFileError(source, "engine.rpm_min", "need rpm_min < rpm_mcr <= rpm_max")
    windage = _windage(r, wind_m)
    cond_names = tuple(str(k) for k in conds_m)
    if not cond_names:
        raise ShipFileError(source, "loading_conditions", "needs at least one condition")
    default_cond = r.text(root, "default_condition", cond_names[0])
    chosen = condition or default_cond
    if chosen not in conds_m:
        raise ShipFileError(
            source, "loading_conditions", f"no condition '{chosen}' (have {list(cond_names)})"
        )
    key = f"loading_conditions.{chosen}"
    c_m = r.section(conds_m[chosen], key)
    cond = LoadingCondition(
        name=chosen,
        draft_fore_m=r.num(c_m, "draft_fore_m", key, 0.5, 30),
        draft_aft_m=r.num(c_m, "draft_aft_m", key, 0.5, 30),
        displacement_t=r.num(c_m, "displacement_t", key, 50, 700000),
        gm_m=r.num(c_m, "gm_m", key, 0.05, 20),
        roll_period_s=r.opt_num(c_m, "roll_period_s", key, 3, 60),
        bulb_area_m2=r.opt_num(c_m, "bulb_area_m2", key, 0, 200),
        bulb_center_height_m=r.opt_num(c_m, "bulb_center_height_m", key, 0, 20),
    )
    if max(cond.draft_fore_m, cond.draft_aft_m) >= hull.depth_m:
        raise ShipFileError(source, key, "drafts must be below hull.depth_m")
    cb = cond.displacement_t / 1.025 / (hull.lwl_m * hull.breadth_m * 0.5 * (
        cond.draft_fore_m + cond.draft_aft_m))
    if not 0.35 < cb < 0.92:
        raise ShipFileError(
            source, f"{key}.displacement_t", f"gives block coefficient {cb:.3f} outside 0.35-0.92"
        )
    seakeeping = SeakeepingSpec(
        max_hs_m=r.num(sk_m, "max_hs_m", "seakeeping", 1, 30, 8.0),
        max_wind_m_s=r.num(sk_m, "max_wind_m_s", "seakeeping", 5, 80, 25.0),
        slamming_probability=r.num(sk_m, "slamming_probability", "seakeeping", 0, 1, 0.04),
        deck_wetness_probability=r.num(sk_m, "deck_wetness_probability", "seakeeping", 0, 1, 0.07),
        propeller_emergence_probability=r.num(
            sk_m, "propeller_emergence_probability", "seakeeping", 0, 1, 0.25
        ),
        roll_resonance_tolerance=r.num(sk_m, "roll_resonance_tolerance", "seakeeping", 0, 1, 0.1),
        min_hs_imo_check_m=r.num(sk_m, "min_hs_imo_check_m", "seakeeping", 0, 20, 2.0),
    )
    water = WaterSpec(
        temperature_c=r.num(water_m, "temperature_c", "water", -2, 35, 15.0),
        salinity_psu=r.num(water_m, "salinity_psu", "water", 0, 42, 35.0),
    )
    sources = root.get("sources", [])
    if not isinstance(sources, list):
        raise ShipFileError(source, "sources", "must be a list of strings")
    digest = hashlib.sha256((text + "\n#condition=" + chosen).encode()).hexdigest()
    return ShipSpec(
        name=name,
        description=str(root.get("description", "")),
        ship_type=ship_type,
        hull=hull,
        propeller=propeller,
        engine=engine,
        windage=windage,
        condition=cond,
        conditions=cond_names,
        seakeeping=seakeeping,
        water=water,
        sources=tuple(str(s) for s in sources),
        content_hash=digest,
        performance_model=_performance_model(root, source),
        economics=parse_economics(root, source),
    )


def _performance_model(root: Mapping[str, Any], source: str) -> str:
    """The file's ``performance_model`` entry with a relative file path made absolute."""
    value = str(root.get("performance_model", "") or "").strip()
    kind, sep, path = value.partition(":")
    if kind not in ("", "physics", "kwon", "profile", "learned") or (kind in (
            "profile", "learned") and not path):
        raise ShipFileError(source, "performance_model",
                            f"'{value}': use physics, kwon, profile:FILE.nc or learned:FILE.nc")
    if sep and not Path(path).is_absolute():
        path = str(Path(source).parent / path)
    return f"{kind}{sep}{path}"


def _windage(r: _Reader, m: Mapping[str, Any]) -> WindageSpec:
    af = r.num(m, "frontal_area_m2", "windage", 10, 5000)
    al = r.num(m, "lateral_area_m2", "windage", 50, 30000)
    set_name = r.text(m, "coefficient_set", "table" if "table" in m else "")
    if set_name == "table":
        t = r.section(m.get("table"), "windage.table")
        ang = r.num_list(t, "relative_angle_deg", "windage.table", 0, 180)
        caa = r.num_list(t, "caa", "windage.table", -3, 3)
        if len(ang) != len(caa) or len(ang) < 2 or ang[0] != 0 or ang[-1] != 180:
            raise ShipFileError(
                r.source, "windage.table", "angles must run 0..180 with one caa per angle"
            )
        if np.any(np.diff(ang) <= 0):
            raise ShipFileError(r.source, "windage.table.relative_angle_deg", "must increase")
        return WindageSpec(af, al, "table", tuple(ang), tuple(caa))
    if set_name not in coefficient_sets():
        raise ShipFileError(
            r.source,
            "windage.coefficient_set",
            f"unknown set '{set_name}' (use 'table' or one of {coefficient_sets()})",
        )
    caa_arr = blendermann_caa(set_name, af, al)
    return WindageSpec(af, al, set_name, TABLE_ANGLES_DEG, tuple(float(x) for x in caa_arr))


class _Reader:
    """Typed access to YAML mappings that raises ``ShipFileError`` naming the key."""

    def __init__(self, source: str) -> None:
        self.source = source

    def section(self, value: Any, key: str) -> Mapping[str, Any]:
        if not isinstance(value, Mapping):
            what = "missing" if value is None else f"a {type(value).__name__}"
            raise ShipFileError(self.source, key or "<root>", f"must be a mapping, got {what}")
        return value

    def text(self, m: Mapping[str, Any], key: str, default: str | None = None) -> str:
        if key not in m:
            if default:
                return default
            raise ShipFileError(self.source, key, "is required")
        return str(m[key])

    def num(
        self,
        m: Mapping[str, Any],
        key: str,
        where: str,
        lo: float,
        hi: float,
        default: float | None = None,
    ) -> float:
        full = f"{where}.{key}" if where else key
        if key not in m or m[key] is None:
            if default is not None:
                return float(default)
            raise ShipFileError(self.source, full, "is required")
        v = m[key]
        if isinstance(v, bool) or not isinstance(v, int | float):
            raise ShipFileError(self.source, full, f"must be a number, got {v!r}")
        if not (lo <= float(v) <= hi):
            raise ShipFileError(self.source, full, f"{v} is outside the valid range {lo}..{hi}")
        return float(v)

    def opt_num(
        self, m: Mapping[str, Any], key: str, where: str, lo: float, hi: float
    ) -> float | None:
        if m.get(key) is None:
            return None
        return self.num(m, key, where, lo, hi)

    def num_list(
        self, m: Mapping[str, Any], key: str, where: str, lo: float, hi: float
    ) -> list[float]:
        full = f"{where}.{key}"
        v = m.get(key)
        if not isinstance(v, list) or not v:
            raise ShipFileError(self.source, full, "must be a non-empty list of numbers")
        out = []
        for i, x in enumerate(v):
            if isinstance(x, bool) or not isinstance(x, int | float) or not lo <= x <= hi:
                raise ShipFileError(
                    self.source, f"{full}[{i}]", f"{x!r} is not a number in {lo}..{hi}"
                )
            out.append(float(x))
        return out
