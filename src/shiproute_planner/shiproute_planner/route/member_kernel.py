"""Route generation on every ensemble member in one compiled call: the member is a
population axis of `_route_kernel.generate_routes`, looped inside numba (no Python loop)."""

from __future__ import annotations

from numba import njit

from . import _route_kernel as rk


@njit(cache=True, nogil=True)
def generate_member_routes(headings, rpm, dep_lon, dep_lat, depart_s, stage_s, arr_lon,
                           arr_lat, rpm_lo, rpm_hi, has_wx, members, times_s, lat0, dlat, lon0,
                           dlon, periodic, chan, isdir, limits, par, r_calm, wake, u_ws, u_sw,
                           m0_ws, m0_sw, caa, sfoc_x, sfoc_y, lon, lat, t, out_f, out_b,
                           heading_n, dist_n, dur_n):
    """Routes of the same genes (pop, ...) sailed on each member k of `members` (M, time, lat,
    lon, channel): nodes (M, pop, n + 2), leg outputs (11|5, M, pop, n + 1), final-leg values
    (M, pop); per member exactly `generate_routes` on that member's fields."""
    for k in range(members.shape[0]):
        rk.generate_routes(headings, rpm, dep_lon, dep_lat, depart_s, stage_s, arr_lon,
                           arr_lat,
                           rpm_lo, rpm_hi, has_wx, members[k], times_s, lat0, dlat, lon0,
                           dlon, periodic, chan, isdir, limits, par, r_calm, wake, u_ws, u_sw,
                           m0_ws, m0_sw, caa, sfoc_x, sfoc_y, lon[k], lat[k], t[k],
                           out_f[:, k], out_b[:, k], heading_n[k], dist_n[k], dur_n[k])
