"""Sea lanes: the shortest lane polyline between two points on the `searoute` network (the
Eurostat/ORNL global shipping lane graph shipped with the `searoute` package)."""

from __future__ import annotations

import functools

import numpy as np
from shiproute_core.geodesy import wrap_lon

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
