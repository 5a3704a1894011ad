"""Compiled clearance walk of great-circle segments on the signed distance to the coast.

Sphere tracing: at each position of a segment the walk reads a lower bound d of the distance
to land (level 0, `geo.coast_distance`, 0.05-deg cells; where its jump would be under
`L0_MIN_JUMP_NM`, level 1, `geo.fine_distance`, full-resolution tiles of 0.0025 deg, a few NM
tighter near the coast) and the clearance c the position
needs (`route.clearance`: open sea, approach zone, free circle round the span ends, narrow
water by the room raster `geo.narrow_water`). With
d >= c + eps every point within d - c is clear and the walk jumps there; with c <= d < c + eps
it steps eps (points within eps keep c - eps); below c the position is a violation. After the
first violation the walk only grades it: inland it jumps by the distance to the sea and
counts the samples jumped over, elsewhere one position stands for the next `GRADE_STEP`
samples. Positions are in sample units of the exact scan's grid (chord fractions k / steps);
a unit is at most `max_arc_per_step` of arc. A tile not yet built before the first violation
makes the segment -1 and its key is written to `missing` (the caller builds, then rescans).
Jumps are bounded with the clearance the span ends ask (narrow water only lowers it), so they
are safe wherever the water type changes. Where the room is below the rule's tight room (water
too narrow for a straight stage leg to follow the full-resolution coast) a search walk counts
only land there, in `tight` instead of `out` (the caller keeps it only where the search's
intermediate coastline agrees: a stage leg through a strait there is threaded at full
resolution by the final repair), jumping within the level-0 cell (same room) as far as the
distance to land allows and across land to the cell's edge; land deeper than `DEEP_LAND_NM`
counts in `out` (inland cells have no room: a leg across a continent would otherwise be
walked to its end and confirmed on the intermediate coastline). A check walk measures the
narrow-water clearance there.
Poleward of the rule's level-1 latitude (a search's latitude bound) level 0 alone decides: a
position it leaves undecided reads as land, so no tile is built there.
A search walk that meets a violation or an unbuilt tile after reading level 1 probes the
segment on level 0 alone from that first read on (`level0_land`; before it the walk's
jumps passed no land): a segment level 0 already puts on land (a candidate across a
continent) takes that count, is not graded further and builds no tile. The verdict never
depends on which tiles a process has built: the first level-1 read lies where level 0 alone
led the walk. A clear walk needs no probe: its jumps never pass land.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..geo.coast_distance import NM_PER_DEG
from ..geo.coast_distance import UNIT_NM as L0_UNIT_NM
from ..geo.fine_distance import FINE_PER_TILE, TILE_DEG
from ..geo.fine_distance import UNIT_NM as L1_UNIT_NM
from ..geo.land_kernels import FINE, segment_ends
from ..geo.narrow_water import UNIT_NM as ROOM_UNIT_NM
from ._route_kernel import max_arc_per_step

GRADE_STEP = 8 * FINE  # samples one graded position stands for after a violation
# level 0 jumps only this far at least [NM]: its bound is a cell diagonal (~3.5 NM) below the
# distance, so its jumps near the coast are tenths of a NM where level 1's are NMs
L0_MIN_JUMP_NM = 1.0
# inland farther than this from the sea [NM] (level 0) land counts even in tight water: the
# intermediate coastline lies within ~0.5 NM (1 km) of the full one
DEEP_LAND_NM = 1.0
L0_PROBE_IN_NM = 0.01  # the level-0 probe's step past a cell's edge [NM]
# the probe's shortest step off inland cells [NM]: a cell's height, so it crosses each coastal
# band (three cells) in about three reads; an inland cell it steps past (a corner cut) is
# found by the walk itself, which then reads level 1 as without the probe
L0_PROBE_MIN_NM = 3.0
_D2R = math.pi / 180.0


@njit(cache=True, nogil=True)
def unit_vector(lat_deg: float, lon_deg: float):
    """Unit vector (x, y, z) of a point on the sphere."""
    la, lo = lat_deg * _D2R, lon_deg * _D2R
    return math.cos(la) * math.cos(lo), math.cos(la) * math.sin(lo), math.sin(la)


@njit(cache=True, nogil=True)
def end_distance_nm(x: float, y: float, z: float, ends: np.ndarray) -> float:
    """Arc [NM] from a point (unit vector) to the nearer span end (`ends`: two unit vectors)."""
    dot = max(x * ends[0] + y * ends[1] + z * ends[2], x * ends[3] + y * ends[4] + z * ends[5])
    return math.acos(min(max(dot, -1.0), 1.0)) / _D2R * NM_PER_DEG


@njit(cache=True, nogil=True)
def clearance_within_nm(q_nm: float, r_nm: float, rule: np.ndarray) -> float:
    """The largest clearance [NM] any point within `r_nm` of a point `q_nm` from the nearer
    span end needs: 0 within the free radius (rule[3]), the approach clearance (rule[1])
    within the approach zone (rule[2]), the open-sea clearance (rule[0]) beyond."""
    need = 0.0
    if q_nm + r_nm > rule[3] and q_nm - r_nm <= rule[2]:
        need = max(need, rule[1])
    if q_nm + r_nm > rule[2]:
        need = max(need, rule[0])
    return need


@njit(cache=True, nogil=True)
def clearance_here_nm(q_nm: float, r_nm: float, room_nm: float, rule: np.ndarray) -> float:
    """The clearance [NM] within `r_nm` of a point `q_nm` from the nearer span end in water of
    `room_nm` (`geo.narrow_water`): narrow water (room below rule[5]) keeps at most the
    approach clearance."""
    c = clearance_within_nm(q_nm, r_nm, rule)
    if room_nm < rule[5]:
        c = min(c, rule[1])
    return c


@njit(cache=True, nogil=True)
def cell_inside_nm(la: float, lo: float, i: int, j: int, cell_deg: float) -> float:
    """Arc [NM] within which every point shares level-0 cell (i, j) with the point (la, lo)
    [deg] in it: the distance to its parallels (along the meridian) and a lower bound of the
    distance to its meridians' great circles (asin(cos la sin dlon) >= 0.999 cos la dlon for
    dlon of a cell)."""
    lat0, lon0 = -90.0 + i * cell_deg, -180.0 + j * cell_deg
    d_lat = min(la - lat0, lat0 + cell_deg - la)
    d_lon = min(lo - lon0, lon0 + cell_deg - lo) * math.cos(la * _D2R) * 0.999
    return max(min(d_lat, d_lon), 0.0) * NM_PER_DEG


@njit(cache=True, nogil=True)
def level1_value(la: float, lo: float, slots, grids, level1_lat: float) -> int:
    """The level-1 cell value at a position (0: on or touching land, else 1 + distance
    steps; 0 poleward of `level1_lat`, where level 1 is not read), or -1 - the tile's key
    when its tile is not built."""
    if abs(la) > level1_lat:
        return 0
    fine_inv = FINE_PER_TILE / TILE_DEG
    gi = min(max(int((la + 90.0) * fine_inv), 0), slots.shape[0] * FINE_PER_TILE - 1)
    gj = min(max(int((lo + 180.0) * fine_inv), 0), slots.shape[1] * FINE_PER_TILE - 1)
    ti, tj = gi // FINE_PER_TILE, gj // FINE_PER_TILE
    slot = slots[ti, tj]
    if slot < 0:
        return -1 - (ti * slots.shape[1] + tj)
    return int(grids[slot, gi - ti * FINE_PER_TILE, gj - tj * FINE_PER_TILE])


@njit(cache=True, nogil=True)
def ask_tile(missing: np.ndarray, n_miss: int, key: int) -> int:
    """Append a tile key to `missing` (not twice in a row; dropped when full: the rescan asks
    again); returns the new count."""
    if n_miss < missing.size and (n_miss == 0 or missing[n_miss - 1] != key):
        missing[n_miss] = key
        n_miss += 1
    return n_miss


@njit(cache=True, nogil=True)
def cell_exit_units(x: float, y: float, z: float, dx: float, dy: float, dz: float,
                    la: float, lo: float, i: int, j: int, cell_deg: float,
                    units_per_f: float) -> float:
    """Sample units from a point (unit vector; la, lo [deg] in level-0 cell (i, j)) of a
    chord-interpolated segment (chord `dx, dy, dz` per unit of chord fraction, `units_per_f`
    units per fraction) to where it leaves the cell, from the rates of latitude and longitude
    there (a segment bends by far less than a cell over one)."""
    w = dx * x + dy * y + dz * z  # tangent of the normalised point: (d - (d.u) u) / |p|
    tx, ty, tz = dx - w * x, dy - w * y, dz - w * z
    h2 = max(x * x + y * y, 1e-18)
    lat_rate = tz / math.sqrt(h2) / _D2R / units_per_f  # deg per unit
    lon_rate = (x * ty - y * tx) / h2 / _D2R / units_per_f
    lat0, lon0 = -90.0 + i * cell_deg, -180.0 + j * cell_deg
    out = 1e30
    if lat_rate > 0.0:
        out = min(out, (lat0 + cell_deg - la) / lat_rate)
    elif lat_rate < 0.0:
        out = min(out, (la - lat0) / -lat_rate)
    if lon_rate > 0.0:
        out = min(out, (lon0 + cell_deg - lo) / lon_rate)
    elif lon_rate < 0.0:
        out = min(out, (lo - lon0) / -lon_rate)
    return max(out, 0.0)


@njit(cache=True, nogil=True)
def level0_land(k_start: float, ax: float, ay: float, az: float, bx: float, by: float,
                bz: float, steps: int, per_nm: float, coast_dist, room, cell_deg: float,
                tight_room_nm: float, near_nm: float) -> int:
    """Samples of a segment (unit-vector ends, `steps` sample units of at most `per_nm`) from
    unit `k_start` on that level 0 alone puts on land (0 when it finds none). It steps to the
    next level-0 cell the segment crosses (a cell's value holds for all of it), at least
    `L0_PROBE_MIN_NM` and farther where the distance to land allows. Land within
    `DEEP_LAND_NM` of tight water's coast is not counted (the search counts it apart). With
    land found, the samples it passed in sea or coastal cells nearer the coast than `near_nm`
    count too, as a graded walk counts them: a leg across an island then weighs at least as
    much as one that only comes too close to its coast over the same stretch."""
    n_lat, n_lon = coast_dist.shape
    inv = 1.0 / cell_deg
    into_next = L0_PROBE_IN_NM / per_nm  # units past a cell's edge: inside the next cell
    count = 0
    near = 0.0  # units passed nearer the coast than near_nm, off inland cells
    k = k_start
    while k <= steps:
        f = k / steps
        x, y, z = ax + f * (bx - ax), ay + f * (by - ay), az + f * (bz - az)
        r = math.sqrt(x * x + y * y + z * z)
        x, y, z = x / r, y / r, z / r
        la = math.asin(max(min(z, 1.0), -1.0)) / _D2R
        lo = math.atan2(y, x) / _D2R
        i = min(max(int((la + 90.0) * inv), 0), n_lat - 1)
        j = min(max(int((lo + 180.0) * inv), 0), n_lon - 1)
        d0 = coast_dist[i, j] * L0_UNIT_NM
        # (the room raster is read only inland: one memory access fewer along coasts)
        if d0 < 0.0 and not (d0 > -DEEP_LAND_NM and room[i, j] * ROOM_UNIT_NM < tight_room_nm):
            # inland: every sample within -d0 is on land
            n = min(1 + int(-d0 / per_nm), steps - int(k) + 1)
            count += n
            k += n
        else:
            exit_k = cell_exit_units(x, y, z, (bx - ax) / r, (by - ay) / r, (bz - az) / r,
                                     la, lo, i, j, cell_deg, float(steps))
            step = max(max(abs(d0), L0_PROBE_MIN_NM) / per_nm, exit_k + into_next)
            if d0 < near_nm:
                near += min(step, steps - k + 1.0)
            k += step
    return count + int(near) if count else 0


@njit(cache=True, nogil=True)
def coarse_clear_nm(la: float, lo: float, coarse, clear_deg, coarse_deg: float) -> float:
    """Arc [NM] from a position to the nearest coarse block with land or coast (0 in one)."""
    c_lat, c_lon = coarse.shape
    ci = min(max(int((la + 90.0) / coarse_deg), 0), c_lat - 1)
    cj = min(max(int((lo + 180.0) / coarse_deg), 0), c_lon - 1)
    return 0.0 if coarse[ci, cj] else clear_deg[ci, cj] * NM_PER_DEG


@njit(cache=True, nogil=True)
def level1_step(la: float, lo: float, i: int, j: int, q_nm: float, room_nm: float,
                apart: bool, per_nm: float, cell_deg: float, slots, grids, rule: np.ndarray):
    """One step of a walk on level 1 at a position (la, lo) [deg] in level-0 cell (i, j),
    `q_nm` from the nearer span end: (units to advance, samples violating, samples on land
    in tight water (`apart`), the key of the tile to build or -1)."""
    v = level1_value(la, lo, slots, grids, rule[8])
    if v < 0:  # tile not built yet
        return 1.0, 0, 0, -1 - v
    eps = rule[4]
    d1 = -1.0 if v == 0 else (v - 1) * L1_UNIT_NM
    c = clearance_within_nm(q_nm, max(d1, 0.0), rule)
    # tight water counts land only, and the points within `inside` share its cell
    inside = cell_inside_nm(la, lo, i, j, cell_deg) if apart else 0.0
    if d1 >= c + eps or (apart and min(d1, inside) >= eps):
        return max(d1 - c, min(d1, inside)) / per_nm, 0, 0, -1
    if d1 >= (0.0 if apart else clearance_here_nm(q_nm, eps, room_nm, rule)):
        return eps / per_nm, 0, 0, -1  # hugging the clearance: points within eps keep c - eps
    if apart:  # on land: so (or tight water) up to the cell's edge
        n = max(1, int(inside / per_nm))
        return float(n), 0, n, -1
    return 1.0, 1, 0, -1


@njit(cache=True, nogil=True)
def clearance_walk(lon0, lat0, lon1, lat1, coarse, clear_deg, coarse_deg, coast_dist, cell_deg,
                   spacing_deg, slots, grids, ends, rule, room, missing, out, tight):
    """Violations per segment (0 = clear; -1 = rescan after the tiles in `missing` are built);
    returns how many tile keys were written to `missing`. `rule`: open-sea clearance,
    approach clearance, approach zone, free radius, eps, narrow room, tight room [NM], search
    (1: skip tight water, 0: measure it), the latitude [deg] poleward of which level 1 is not
    read (a position level 0 leaves undecided there reads as land); `ends`: the span ends'
    unit vectors (6,); `room`: uint8 room per level-0 cell [0.1 NM]; `tight` (out): a search
    walk's violations in tight water, not in `out`. A jump of length L from a point with
    bound d needs d - L at least the clearance of every point it passes
    (`clearance_within_nm` over d)."""
    n_lat, n_lon = coast_dist.shape
    inv = 1.0 / cell_deg
    c_max = max(rule[0], rule[1])
    near_nm = c_max + L0_MIN_JUMP_NM  # the probe counts samples nearer the coast than this
    search = rule[7] > 0.5
    n_miss = 0
    for s in range(lon0.size):
        ax, ay, az, bx, by, bz, arc = segment_ends(lat0[s], lon0[s], lat1[s], lon1[s])
        steps = FINE * max(1, math.ceil(arc / spacing_deg))
        per_nm = max_arc_per_step(arc, steps) * NM_PER_DEG  # NM per sample unit, at most
        count = 0
        unresolved = False
        consulted = False  # a search read (or asked for) level 1 on this segment
        k_read = 0.0  # where it first did: no land level 0 shows lies before it
        probed = False
        on_land = 0
        n_miss0 = n_miss
        tight[s] = 0
        k = 0.0
        while k <= steps:
            if consulted and not probed and (count or unresolved):  # trouble after a read
                probed = True
                on_land = level0_land(k_read, ax, ay, az, bx, by, bz, steps, per_nm,
                                      coast_dist, room, cell_deg, rule[6], near_nm)
                if on_land:  # level 0 decides: no grading, no tile
                    break
            f = k / steps
            x, y, z = ax + f * (bx - ax), ay + f * (by - ay), az + f * (bz - az)
            r = math.sqrt(x * x + y * y + z * z)
            x, y, z = x / r, y / r, z / r
            la = math.asin(max(min(z, 1.0), -1.0)) / _D2R
            lo = math.atan2(y, x) / _D2R
            beyond = 0.0 if count else coarse_clear_nm(la, lo, coarse, clear_deg, coarse_deg)
            if beyond - c_max > per_nm:
                k += (beyond - c_max) / per_nm
                continue
            i = min(max(int((la + 90.0) * inv), 0), n_lat - 1)
            j = min(max(int((lo + 180.0) * inv), 0), n_lon - 1)
            d0 = coast_dist[i, j] * L0_UNIT_NM
            if d0 >= c_max + L0_MIN_JUMP_NM:  # sea far enough from the coast for any clearance
                k += max((d0 - c_max) / per_nm, GRADE_STEP if count else 0.0)
                continue
            room_nm = room[i, j] * ROOM_UNIT_NM
            # tight water: counted apart (not deep inland: the intermediate coastline is land
            # there too, and a leg across a continent is graded at level 0)
            apart = search and room_nm < rule[6] and d0 > -DEEP_LAND_NM
            if d0 < 0.0:  # inland: every sample within -d0 is on land
                n = min(1 + int(-d0 / per_nm), steps - int(k) + 1) if count or apart else 1
                if apart:
                    tight[s] += n
                else:
                    count += n
                k += n
                continue
            q = end_distance_nm(x, y, z, ends)
            c = clearance_within_nm(q, d0, rule)
            if d0 >= c + L0_MIN_JUMP_NM:
                k += max((d0 - c) / per_nm, GRADE_STEP if count else 0.0)
                continue
            if count:  # a violation already: the count only grades it (level 0 only)
                count += GRADE_STEP
                k += GRADE_STEP
                continue
            if search and not consulted:
                k_read = k
            consulted = search
            dk, n_out, n_tight, key = level1_step(la, lo, i, j, q, room_nm, apart, per_nm,
                                                  cell_deg, slots, grids, rule)
            if key >= 0:  # tile not built yet
                unresolved = True
                n_miss = ask_tile(missing, n_miss, key)
            count += n_out
            tight[s] += n_tight
            k += dk
        if consulted and not probed and (count or unresolved or tight[s]):
            on_land = level0_land(k_read, ax, ay, az, bx, by, bz, steps, per_nm, coast_dist,
                                  room, cell_deg, rule[6], near_nm)
        if on_land:  # level 0 decides: no tile asked for, nothing counted apart
            out[s], tight[s], n_miss = on_land, 0, n_miss0
        else:
            out[s] = -1 if unresolved else count
    return n_miss
