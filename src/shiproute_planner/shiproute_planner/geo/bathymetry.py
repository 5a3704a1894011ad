"""Bathymetry grids (GEBCO, ETOPO, EMODnet and other CF lat/lon grids) -> water depth.

A grid file is read once into a `DepthGrid`: depth in metres positive down on a regular
latitude/longitude grid (rows south to north). The sign convention is taken from the
variable's CF attributes (`positive`, `standard_name`) or, failing those, its name
(`elevation`, `z`, `ROSE` are heights; `depth`, `deptho` are depths). Several grids form a
`Bathymetry`; where they overlap the finest one answers (see `geo.depth_scan`).

Cells at or above the datum are land or drying: a fine grid (<= 1 arc-minute) reports them as
0 m of water; a coarse grid reports them and the cells next to them as unknown, because its
coastal cells average sea and land over several kilometres and the coastline, not the grid,
decides there, and reports the median of each 3 x 3 neighbourhood (a shoal must cover most
of it, ~15 km at 5 arc-minutes, to count: single-cell values are as often errors). Cells of a
coarse grid near GSHHG land are unknown too (`geo.coarse_coast`: smear, not shoals).
"""

from __future__ import annotations

import dataclasses
import functools
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import BathymetryError
from . import coarse_coast, depth_cache

# Debian package ferret-datasets: ETOPO5 (NOAA NGDC 1988, 5 arc-minute, public domain)
ETOPO5_PATH = Path("/usr/share/ferret-vis/data/etopo5.cdf")
FINE_GRID_DEG = 1.0 / 60.0 + 1e-9  # grids this fine or finer are trusted up to the coast

_HEIGHT_NAMES = ("elevation", "z", "rose", "topo", "height", "altitude", "band1", "elev")
_DEPTH_NAMES = ("depth", "deptho", "bathymetry", "bathy", "sea_floor_depth")
_HEIGHT_STD = ("height_above_reference_ellipsoid", "height_above_mean_sea_level",
               "height_above_geopotential_datum", "altitude", "height",
               "surface_altitude", "bedrock_altitude")
_DEPTH_STD = ("sea_floor_depth_below_sea_surface", "sea_floor_depth_below_geoid",
              "sea_floor_depth_below_mean_sea_level", "depth")


@dataclass(frozen=True, eq=False)
class DepthGrid:
    """Water depth [m, positive down; NaN unknown] on a regular lat/lon grid."""

    name: str
    depth_m: np.ndarray  # (n_lat, n_lon) float32, row 0 southernmost
    lat0_deg: float  # centre of row 0
    dlat_deg: float
    lon0_deg: float  # centre of column 0, in -180..180
    dlon_deg: float
    periodic: bool  # the columns wrap round the globe
    #: coarse grids: uint8 mask, 1 where the cell is within `coarse_coast.COAST_CELLS` of
    #: GSHHG land (its depth is NaN: not trusted); None for fine grids
    coast_cells: np.ndarray | None = None

    @property
    def cell_deg(self) -> float:
        """Grid spacing [deg] (the larger of the two)."""
        return max(self.dlat_deg, self.dlon_deg)

    @property
    def resolution_text(self) -> str:
        """Spacing in arc-seconds or arc-minutes, as charts and data sets state it."""
        arcsec = self.cell_deg * 3600.0
        return f"{arcsec:.0f} arc-second" if arcsec < 60.0 else f"{arcsec / 60.0:.0f} arc-minute"

    @property
    def is_coarse(self) -> bool:
        """Coarser than 1 arc-minute: coastal cells are smeared."""
        return self.cell_deg > FINE_GRID_DEG


def _pick_variable(ds, path: Path):
    """The depth or height variable of a dataset, and whether it is positive up."""
    two_d = [v for v in ds.data_vars.values() if v.ndim == 2 and np.issubdtype(v.dtype, np.number)]
    for var in two_d:
        std = str(var.attrs.get("standard_name", "")).lower()
        positive = str(var.attrs.get("positive", "")).lower()
        if positive in ("up", "down") and (std in _HEIGHT_STD + _DEPTH_STD
                                            or var.name.lower() in _HEIGHT_NAMES + _DEPTH_NAMES):
            return var, positive == "up"
        if std in _HEIGHT_STD:
            return var, True
        if std in _DEPTH_STD:
            return var, False
    for var in two_d:
        name = str(var.name).lower()
        if name in _HEIGHT_NAMES:
            return var, str(var.attrs.get("positive", "up")).lower() != "down"
        if name in _DEPTH_NAMES:
            return var, str(var.attrs.get("positive", "down")).lower() != "down"
    names = ", ".join(str(v) for v in ds.data_vars) or "none"
    raise BathymetryError(
        f"bathymetry file {path}: no depth or elevation variable found (2-D variables named "
        f"elevation/z/depth or with a CF standard_name such as sea_floor_depth_below_sea_"
        f"surface; the file has: {names})")


_AXIS_UNITS = {"lat": ("degrees_north", "degree_north", "degrees_n", "degree_n"),
               "lon": ("degrees_east", "degree_east", "degrees_e", "degree_e")}
_AXIS_NAMES = {"lat": ("lat", "latitude", "y", "etopo05_y", "nav_lat"),
               "lon": ("lon", "longitude", "x", "etopo05_x", "nav_lon")}
_AXIS_LETTER = {"lat": "Y", "lon": "X"}


def _axis_kind(coord) -> str:
    """'lat', 'lon', 'projected' or '' for one coordinate variable."""
    units = str(coord.attrs.get("units", "")).lower()
    std = str(coord.attrs.get("standard_name", "")).lower()
    letter = str(coord.attrs.get("axis", "")).upper()
    name = str(coord.name).lower()
    if units in ("m", "metre", "metres", "meter", "meters", "km") or std.startswith(
            "projection_"):
        return "projected"
    for kind in ("lat", "lon"):
        if units in _AXIS_UNITS[kind] or std == ("latitude" if kind == "lat" else "longitude"):
            return kind
    for kind in ("lat", "lon"):
        if (letter == _AXIS_LETTER[kind] or name in _AXIS_NAMES[kind]) and units in (
                "", "degrees", "degree", "deg"):
            return kind
    return ""


def _axes(var, ds, path: Path) -> tuple[str, np.ndarray, str, np.ndarray]:
    """(lat dim, lat values, lon dim, lon values) of a 2-D variable, degrees checked."""
    found: dict[str, tuple[str, np.ndarray]] = {}
    for dim in var.dims:
        if dim not in ds.variables:
            continue
        kind = _axis_kind(ds[dim])
        if kind == "projected":
            raise BathymetryError(
                f"bathymetry file {path}: axis {dim!r} is in "
                f"{ds[dim].attrs.get('units', 'metres')} (a projected CRS); give a "
                "latitude/longitude grid in degrees (EPSG:4326), e.g. gdalwarp -t_srs EPSG:4326")
        if kind:
            found[kind] = (str(dim), np.asarray(ds[dim].values, dtype=np.float64))
    if set(found) != {"lat", "lon"}:
        raise BathymetryError(
            f"bathymetry file {path}: variable {var.name!r} needs latitude and longitude axes "
            f"in degrees (dimensions {', '.join(map(str, var.dims))}); only regular lat/lon "
            "grids are read")
    return (*found["lat"], *found["lon"])


def _check_crs(ds, var, path: Path) -> None:
    """Refuse grids whose CF grid mapping is not plain latitude/longitude."""
    mapping = var.attrs.get("grid_mapping")
    if mapping and mapping in ds.variables:
        gm = str(ds[mapping].attrs.get("grid_mapping_name", "latitude_longitude"))
        if gm != "latitude_longitude":
            raise BathymetryError(
                f"bathymetry file {path}: grid mapping {gm!r} is not latitude_longitude; "
                "reproject it to EPSG:4326 first (e.g. gdalwarp -t_srs EPSG:4326)")


def _regular_step(values: np.ndarray, path: Path, kind: str) -> float:
    step = np.diff(values)
    if values.size < 2 or not np.allclose(step, step[0], rtol=1e-3, atol=1e-9) or step[0] == 0:
        raise BathymetryError(f"bathymetry file {path}: the {kind} axis is not regularly spaced")
    return float(step[0])


@functools.lru_cache(maxsize=8)
def load_depth_grid(path_text: str) -> DepthGrid:
    """Read one bathymetry NetCDF file into a `DepthGrid` (cached per path); a coarse grid
    prepared before is memory-mapped from the data directory instead (see `geo.depth_cache`)."""
    from .datadir import data_dir

    path = Path(path_text)
    if not path.is_file():
        raise BathymetryError(f"bathymetry file {path} does not exist")
    key = prepared_key(path)
    prepared = depth_cache.open_prepared(data_dir(), key)
    mask = None if prepared is None else coarse_coast.open_mask(data_dir(), key,
                                                                 prepared[0].shape)
    if prepared is not None and mask is not None:
        depth, meta = prepared
        return DepthGrid(str(meta["name"]), depth, float(meta["lat0_deg"]),
                         float(meta["dlat_deg"]), float(meta["lon0_deg"]),
                         float(meta["dlon_deg"]), bool(meta["periodic"]), mask)
    grid = _read_grid(path)
    grid = _prepare(grid)
    if not np.isfinite(grid.depth_m).any():
        raise BathymetryError(f"bathymetry file {path}: it holds no sea depths")
    if grid.is_coarse and grid.coast_cells is not None:  # seconds: kept, mapped from now on
        coarse_coast.write_mask(data_dir(), key, grid.coast_cells)
        depth_cache.write_prepared(data_dir(), key, grid.depth_m, {
            "name": grid.name, "lat0_deg": grid.lat0_deg, "dlat_deg": grid.dlat_deg,
            "lon0_deg": grid.lon0_deg, "dlon_deg": grid.dlon_deg, "periodic": grid.periodic})
    return grid


def _read_grid(path: Path) -> DepthGrid:
    """The depth variable of a NetCDF file as a `DepthGrid` (not yet prepared)."""
    import xarray as xr

    try:
        ds = xr.open_dataset(path, decode_times=False)
    except (OSError, ValueError) as exc:
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise BathymetryError(f"bathymetry file {path} is not a readable NetCDF grid "
                              f"({first})") from None
    with ds:
        var, up = _pick_variable(ds, path)
        _check_crs(ds, var, path)
        lat_dim, lat, lon_dim, lon = _axes(var, ds, path)
        values = np.asarray(var.transpose(lat_dim, lon_dim).values, dtype=np.float32)
    if values.shape != (lat.size, lon.size):
        raise BathymetryError(f"bathymetry file {path}: {var.name!r} is not (lat, lon)")
    dlat = _regular_step(lat, path, "latitude")
    dlon = _regular_step(lon, path, "longitude")
    if dlat < 0:
        lat, values, dlat = lat[::-1], values[::-1], -dlat
    if dlon < 0:
        lon, values, dlon = lon[::-1], values[:, ::-1], -dlon
    if not (lat[0] >= -90.5 and lat[-1] <= 90.5):
        raise BathymetryError(f"bathymetry file {path}: latitudes {lat[0]}..{lat[-1]} are not "
                              "degrees (is it a projected grid?)")
    depth = -values if up else values.copy()
    periodic = dlon * lon.size >= 360.0 - 1e-6
    if periodic and lon.size * dlon > 360.0 + 1e-6:  # duplicated seam column
        n = round(360.0 / dlon)
        lon, depth = lon[:n], depth[:, :n]
    lon0 = float((lon[0] + 180.0) % 360.0 - 180.0)
    return DepthGrid(path.name, np.ascontiguousarray(depth, dtype=np.float32),
                     float(lat[0]), dlat, lon0, dlon, bool(periodic))


#: version of the preparation below; a change makes every prepared grid be prepared again
PREPARED_VERSION = 4


def prepared_key(path: Path) -> str:
    """Cache key of a grid file's prepared depths: name, size, modification time, version and
    the coastal reach."""
    st = path.stat()
    return (f"{path.name}_{st.st_size}_{int(st.st_mtime)}_v{PREPARED_VERSION}"
            f"_coast{coarse_coast.COAST_CELLS}")


def _prepare(grid: DepthGrid) -> DepthGrid:
    """Dry and coastal cells as the grid's resolution allows (see the module docstring), in
    place; a coarse grid comes back with its coastal-cell mask (`geo.coarse_coast`)."""
    if grid.is_coarse:  # a compilation's shelf fill values are "shallow, not known"
        from .fill_values import shelf_fill_values

        grid.depth_m[np.isin(grid.depth_m, shelf_fill_values(grid.depth_m))] = np.nan
    dry = grid.depth_m <= 0.0
    if grid.is_coarse:  # dry cells and their neighbours: the coastline decides there
        from scipy import ndimage

        near = ndimage.binary_dilation(dry, structure=np.ones((3, 3), dtype=bool))
        if grid.periodic:  # the seam columns see each other
            near[:, 0] |= dry[:, -1]
            near[:, -1] |= dry[:, 0]
        coast = coarse_coast.coastal_cells(grid.depth_m.shape, grid.lat0_deg, grid.dlat_deg,
                                           grid.lon0_deg, grid.dlon_deg, grid.periodic)
        # each coarse cell reads the median of its 3 x 3 neighbourhood: single cells of
        # 5-arc-minute compilations are as often errors as shoals (shoals that small need a
        # finer grid anyway), banks several cells wide stay shallow
        known = np.where(np.isnan(grid.depth_m) | near, np.inf, grid.depth_m)
        median = ndimage.median_filter(known, size=3, mode="wrap" if grid.periodic
                                       else "nearest")
        # cells near GSHHG land give no depth; they still vote in their neighbours' median,
        # which keeps a shoal that reaches offshore at least as shallow as before
        grid.depth_m[:] = np.where(near | coast | ~np.isfinite(median), np.nan, median)
        return dataclasses.replace(grid, coast_cells=coast.astype(np.uint8))
    grid.depth_m[dry] = 0.0
    return grid


def default_depth_files() -> list[Path]:
    """Bundled coarse global depth: ETOPO5 from Debian's ferret-datasets, if installed."""
    return [ETOPO5_PATH] if ETOPO5_PATH.is_file() else []
