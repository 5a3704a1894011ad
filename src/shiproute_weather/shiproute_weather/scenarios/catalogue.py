"""Bundled, deterministic forecast scenarios written as NetCDF and read back by the loader.

`storm_march`: North Pacific, cycle 2026-03-03T12Z, a Holland-profile extratropical storm
deepening off Japan and crossing the Busan -> Long Beach great circle near the dateline.
`storm_march_cycle2`: the next cycle (6 h later) with the storm 6 h slower and shifted
north-east. `calm_june`: the same region in June without a storm. All: 0.5 deg grid over
10..62 N, 115..245 E, 3-hourly for 16 days (129 valid times).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import xarray as xr

from ..contract import canonical as cv
from ..errors import ScenarioError
from .ensemble import EnsembleSpec, member_fields, spread_summary
from .synth_seas import JUNE_SWELL, MARCH_SWELL, BackgroundSwell
from .synth_wind import JUNE, MARCH, Season, TrackPoint

LAT_RANGE_DEG = (10.0, 62.0)
LON_RANGE_DEG = (115.0, 245.0)
SPACING_DEG = 0.5
STEP_H = 3.0
LENGTH_H = 384.0
FORMAT_VERSION = "4"

# Storm track, hours after 2026-03-03T12Z: (h, lat, lon, dp hPa, Rmax km, Holland B).
# Deepening to ~968 hPa: a strong but ordinary winter North Pacific storm.
_TRACK_MARCH = [
    TrackPoint(36.0, 31.0, 136.0, 8.0, 300.0, 1.15),
    TrackPoint(60.0, 34.0, 142.0, 22.0, 320.0, 1.2),
    TrackPoint(84.0, 38.0, 150.0, 34.0, 340.0, 1.2),
    TrackPoint(108.0, 42.0, 159.0, 42.0, 360.0, 1.25),
    TrackPoint(132.0, 45.5, 168.0, 45.0, 380.0, 1.25),
    TrackPoint(156.0, 48.5, 177.0, 42.0, 400.0, 1.2),
    TrackPoint(180.0, 51.0, 186.0, 34.0, 420.0, 1.2),
    TrackPoint(216.0, 53.5, 196.0, 26.0, 450.0, 1.15),
    TrackPoint(252.0, 55.0, 204.0, 10.0, 450.0, 1.1),
]


def _shifted(track: list[TrackPoint], delay_h: float, dlat: float, dlon: float,
             ddp: float) -> list[TrackPoint]:
    """Track of a later cycle: the storm later and displaced, growing with lead time."""
    out = []
    for p in track:
        share = min(1.0, max(0.0, (p.hours - 36.0) / 96.0))
        out.append(TrackPoint(p.hours + delay_h, p.lat_deg + dlat * share,
                              p.lon_deg + dlon * share, max(p.dp_hpa + ddp * share, 0.0),
                              p.rmax_km, p.holland_b))
    return out


@dataclass(frozen=True)
class ScenarioSpec:
    """Everything that defines one scenario (times are UTC)."""

    name: str
    reference_time: str  # model run, ISO 8601 UTC
    epoch: str  # origin of track hours and of the background wave phases
    season: Season
    swell: BackgroundSwell
    seed: int
    track: list[TrackPoint] = field(default_factory=list)
    description: str = ""


SCENARIOS: dict[str, ScenarioSpec] = {
    "storm_march": ScenarioSpec(
        "storm_march", "2026-03-03T12:00:00", "2026-03-03T12:00:00", MARCH, MARCH_SWELL, 20260303,
        _TRACK_MARCH, "North Pacific, March 2026: storm crossing the Busan-Long Beach route"),
    "storm_march_cycle2": ScenarioSpec(
        "storm_march_cycle2", "2026-03-03T18:00:00", "2026-03-03T12:00:00", MARCH, MARCH_SWELL,
        20260303, _shifted(_TRACK_MARCH, 6.0, 1.5, 3.0, 3.0),
        "Next cycle of storm_march (6 h later): storm slower, further north-east, deeper"),
    "calm_june": ScenarioSpec(
        "calm_june", "2026-06-03T12:00:00", "2026-06-03T12:00:00", JUNE, JUNE_SWELL, 20260603,
        [], "North Pacific, June 2026: weak westerlies, trades, southern swell, no storm"),
}


#: ensemble scenarios (`scenarios.ensemble`: spread model and its sources): 1 deg, 6-hourly
ENSEMBLES: dict[str, EnsembleSpec] = {
    "storm_march_ensemble": EnsembleSpec(
        "storm_march", 20, 1.0, 6.0, 20260304,
        "storm_march as a 20-member ensemble: storm timing, track, intensity and size "
        "perturbed, spread growing with lead time"),
}


def scenario_names() -> list[str]:
    """Names of the bundled scenarios."""
    return [*SCENARIOS, *ENSEMBLES]


def _spec(name: str) -> ScenarioSpec:
    if name in ENSEMBLES:
        return SCENARIOS[ENSEMBLES[name].base]
    try:
        return SCENARIOS[name]
    except KeyError:
        raise ScenarioError(f"unknown scenario {name!r}; expected one of "
                            f"{', '.join(scenario_names())}") from None


def _stored(name: str, a: np.ndarray) -> np.ndarray:
    """float32 at 0.01 (0.1 deg for directions); rounded directions wrapped into [0, 360)."""
    if name in cv.DIRECTION_VARIABLES:
        return (np.round(a, 1) % 360.0).astype(np.float32)
    return np.round(a, 2).astype(np.float32)


def build_scenario(name: str) -> xr.Dataset:
    """Generate a scenario in memory as a canonical dataset (deterministic for a name)."""
    from .fields import build_fields  # numba-heavy: only when generating

    spec = _spec(name)
    ens = ENSEMBLES.get(name)
    spacing, step = (ens.spacing_deg, ens.step_h) if ens else (SPACING_DEG, STEP_H)
    lat = np.arange(LAT_RANGE_DEG[0], LAT_RANGE_DEG[1] + 1e-9, spacing)
    lon = np.arange(LON_RANGE_DEG[0], LON_RANGE_DEG[1] + 1e-9, spacing)
    ref = np.datetime64(spec.reference_time, "ns")
    offset_h = float((ref - np.datetime64(spec.epoch, "ns")) / np.timedelta64(1, "h"))
    lead_h = np.arange(0.0, LENGTH_H + 1e-9, step)
    times = ref + (lead_h * 3600).astype("timedelta64[s]").astype("timedelta64[ns]")
    coords: dict = {"time": times, "latitude": lat, "longitude": lon}
    data: dict[str, tuple[tuple[str, ...], np.ndarray]]
    if ens is not None:
        members = member_fields(spec, ens, lat, lon, lead_h + offset_h, offset_h)
        data = {n: (("member", "time", "latitude", "longitude"),
                    np.stack([_stored(n, f[n]) for f in members])) for n in members[0]}
        coords = {"member": np.arange(ens.members, dtype=np.int64), **coords,
                  "member_label": ("member", ["control"] + [f"perturbed {k}" for k in
                                                           range(1, ens.members)])}
    else:
        fields = build_fields(spec.season, spec.swell, spec.track,
                              np.random.default_rng(spec.seed), lat, lon, lead_h + offset_h)
        data = {n: (("time", "latitude", "longitude"), _stored(n, a))
                for n, a in fields.items()}
    ds = xr.Dataset(
        data,
        coords=coords,
        attrs={"forecast_reference_time": spec.reference_time + "Z",
               "source": f"shiproute synthetic scenario {name} v{FORMAT_VERSION}",
               "cycle_id": f"{name}-{spec.reference_time[:13].replace('-', '').replace('T', '')}",
               "title": ens.description if ens else spec.description},
    )
    if ens is not None:
        ds.attrs.update(member_kind="ensemble", ensemble_spread=spread_summary())
    return cv.annotate(ds)


def write_scenario(name: str, path: Path) -> Path:
    """Generate a scenario and write it as uncompressed float32 NetCDF-4 (atomic rename).

    The file is a local cache read on every load, so it is stored contiguous and without
    compression: reading it is a plain copy instead of a zlib decompression.
    """
    ds = build_scenario(name)
    enc = {n: {"zlib": False, "contiguous": True, "dtype": "float32",
               "_FillValue": np.float32(np.nan)} for n in ds.data_vars}
    if name in ENSEMBLES:  # 16-bit CF packing at the stored 0.01 (0.1 deg): half the bytes
        enc = {n: {"zlib": False, "contiguous": True, "dtype": "int16", "_FillValue": -32768,
                   "scale_factor": np.float32(0.1 if n in cv.DIRECTION_VARIABLES else 0.01),
                   "add_offset": np.float32(0.0)} for n in ds.data_vars}
    enc["time"] = {"units": f"hours since {_spec(name).reference_time}", "dtype": "float64",
                   "calendar": "proleptic_gregorian"}
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(f".tmp{os.getpid()}")
    ds.to_netcdf(tmp, engine="netcdf4", encoding=enc)
    tmp.replace(path)
    return path


def data_dir() -> Path:
    """Cache directory: $SHIPROUTE_DATA_DIR, else ~/.cache/shiproute."""
    env = os.environ.get("SHIPROUTE_DATA_DIR")
    return Path(env) if env else Path.home() / ".cache" / "shiproute"


def scenario_path(name: str, rebuild: bool = False) -> Path:
    """Path of a scenario's NetCDF file, generating it on first use."""
    _spec(name)
    path = data_dir() / "scenarios" / f"{name}.v{FORMAT_VERSION}.nc"
    if rebuild or not path.exists():
        write_scenario(name, path)
        for old in path.parent.glob(f"{name}.v*.nc"):  # caches of earlier format versions
            if old != path:
                old.unlink(missing_ok=True)
    return path


def scenario_dataset(name: str) -> xr.Dataset:
    """A scenario as a canonical dataset, loaded from its NetCDF file through the loader."""
    if name in ENSEMBLES:  # members kept, read lazily: a sampler packs one member at a time
        return cv.annotate(xr.open_dataset(scenario_path(name), engine="netcdf4"))
    from ..ingest.loaders import open_forecast

    return open_forecast([scenario_path(name)])
