"""The box of a voyage's region: between two points the shorter way round in longitude,
widened by margins (the tiles and coastline cells a warm-up prepares lie in it)."""

from __future__ import annotations

LAT_CAP_DEG = 85.0  # the box's latitudes are capped here (no tile or cell beyond is needed)


def region_box(a: tuple[float, float], b: tuple[float, float],
               margins_deg: tuple[float, float, float, float]
               ) -> tuple[float, float, float, float]:
    """(lon_min, lon_max, lat_min, lat_max) [deg] of the box between `a` and `b` ((lon, lat)
    [deg]; the shorter way round in longitude, so lon_max may pass 180) widened by (west,
    east, south, north) margins [deg], latitudes capped at +-LAT_CAP_DEG."""
    if (b[0] - a[0]) % 360.0 > 180.0:  # westward is shorter: the box runs from b east to a
        a, b = b, a
    east = a[0] + (b[0] - a[0]) % 360.0
    west_m, east_m, south_m, north_m = margins_deg
    return (a[0] - west_m, east + east_m, max(min(a[1], b[1]) - south_m, -LAT_CAP_DEG),
            min(max(a[1], b[1]) + north_m, LAT_CAP_DEG))
