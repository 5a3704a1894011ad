"""Where a published plan puts the ship some hours after departure (re-plan starts, benches)."""

from __future__ import annotations

import numpy as np
from shiproute_core.geodesy import direct, inverse

from .plan_types import RoutePlan


def position_after(plan: RoutePlan, hours: float) -> tuple[float, float, float]:
    """(lat [deg], lon [deg], time [POSIX s]) on `plan` `hours` after its departure, on the
    geodesic of the leg sailed then (clamped to the first and last legs)."""
    lon, lat, t = plan.track()
    now = plan.departure_s + hours * 3600.0
    k = int(np.clip(np.searchsorted(t, now, side="right") - 1, 0, t.size - 2))
    az, d = inverse(lon[k], lat[k], lon[k + 1], lat[k + 1])
    f = (now - t[k]) / max(t[k + 1] - t[k], 1.0)
    plon, plat = direct(lon[k], lat[k], az, d * f)
    return float(plat), float(plon), now
