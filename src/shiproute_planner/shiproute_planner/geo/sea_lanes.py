"""Sea lanes: the shortest lane polyline between two points on the `searoute` network (the
Eurostat/ORNL global shipping lane graph shipped with the `searoute` package)."""

from __future__ import annotations

import functools

import numpy as np
from shiproute_core.geodesy import unwrap_near, wrap_lon

#: end points are rounded to this many decimals of a degree (~11 m) before the lookup, so
#: nearby requests share the cache
LANE_END_DECIMALS = 4


#: searoute's passage names a lane always avoids (its own default: the Northwest Passage)
ALWAYS_AVOIDED = ("northwest",)


@functools.lru_cache(maxsize=64)
def searoute_coords(lon0: float, lat0: float, lon1: float, lat1: float,
                    avoid: tuple[str, ...] = ()) -> np.ndarray | None:
    """searoute's shortest sea-lane polyline as (k, 2) lon/lat in degrees, kept out of the
    passages `avoid` names besides `ALWAYS_AVOIDED` (cached: its Dijkstra is slow); None when
    it finds no route. The array is shared: callers copy before changing it."""
    import searoute

    try:
        feat = searoute.searoute([lon0, lat0], [lon1, lat1],
                                 restrictions=[*ALWAYS_AVOIDED, *avoid])
    except Exception:
        return None
    return np.asarray(feat["geometry"]["coordinates"], dtype=float)


def lane_key(lon0_deg: float, lat0_deg: float, lon1_deg: float, lat1_deg: float
             ) -> tuple[float, float, float, float]:
    """A lane's end points as the caches key them: longitudes wrapped to [-180, 180), all
    rounded to `LANE_END_DECIMALS`, so nearby requests share one lookup."""
    d = LANE_END_DECIMALS
    return (round(float(wrap_lon(lon0_deg)), d), round(float(lat0_deg), d),
            round(float(wrap_lon(lon1_deg)), d), round(float(lat1_deg), d))


def sea_lane_between(lon0_deg: float, lat0_deg: float, lon1_deg: float, lat1_deg: float,
                     avoid: tuple[str, ...] = ()) -> np.ndarray | None:
    """The sea-lane polyline from (lon0, lat0) to (lon1, lat1) (ends keyed by `lane_key`),
    kept out of the searoute passages `avoid` names; its ends are searoute's network nodes
    nearest to the points, not the points themselves. None when there is no route."""
    return searoute_coords(*lane_key(lon0_deg, lat0_deg, lon1_deg, lat1_deg), tuple(avoid))


def _nearest_on_lane(lon: np.ndarray, lat: np.ndarray, lon_deg: float, lat_deg: float,
                     last: bool) -> tuple[int, float]:
    """(segment k, fraction t) of the point of a polyline (continuous longitudes) nearest to
    (lon_deg, lat_deg), in a plane tangent there (longitude scaled by the cosine of the
    latitude): exact enough for the segments near the point, which are the ones that win.
    Ties go to the first segment, or the last with `last`."""
    scale = np.cos(np.radians(lat_deg))
    x = (unwrap_near(lon, lon_deg) - lon_deg) * scale
    y = lat - lat_deg
    dx, dy = np.diff(x), np.diff(y)
    t = np.clip(-(x[:-1] * dx + y[:-1] * dy) / np.maximum(dx * dx + dy * dy, 1e-18), 0.0, 1.0)
    d2 = (x[:-1] + t * dx) ** 2 + (y[:-1] + t * dy) ** 2
    k = int(d2.size - 1 - np.argmin(d2[::-1])) if last else int(np.argmin(d2))
    return k, float(t[k])


def lane_between_points(coords: np.ndarray, lon0_deg: float, lat0_deg: float,
                        lon1_deg: float, lat1_deg: float) -> np.ndarray:
    """The part of a sea-lane polyline ((k, 2) lon/lat) between its points nearest to
    (lon0, lat0) and to (lon1, lat1), those points included, as a new array. `searoute`
    ends a lane at the network nodes nearest the end points; a point in open water between
    two far-apart nodes (a shoal passage's gate on the lane) snaps to a node past it, and a
    track through that node would run on and turn back over what lies beyond (the shoal)."""
    lon = np.unwrap(np.asarray(coords[:, 0], dtype=float), period=360.0)
    lat = np.asarray(coords[:, 1], dtype=float)
    if lon.size < 2:
        return np.column_stack([lon, lat])
    k0, t0 = _nearest_on_lane(lon, lat, lon0_deg, lat0_deg, last=False)
    k1, t1 = _nearest_on_lane(lon, lat, lon1_deg, lat1_deg, last=True)
    if (k1, t1) < (k0, t0):  # the ends project in reverse order: keep the lane as it is
        return np.column_stack([lon, lat])

    def at(k: int, t: float) -> tuple[float, float]:
        return (float(lon[k] + t * (lon[k + 1] - lon[k])),
                float(lat[k] + t * (lat[k + 1] - lat[k])))

    inner = np.column_stack([lon[k0 + 1:k1 + 1], lat[k0 + 1:k1 + 1]]).reshape(-1, 2)
    return np.vstack([at(k0, t0), inner, at(k1, t1)])
