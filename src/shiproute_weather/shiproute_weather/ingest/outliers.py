"""Physically impossible forecast values become missing (NaN), counted per field.

Limits: `contract.limits`. A field whose valid values are mostly impossible is not a forecast:
the file is refused instead.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..contract import canonical as cv
from ..contract.limits import CURRENT_SPEED_MAX_M_S, HS_MAX_M, PERIOD_MAX_S, WIND_SPEED_MAX_M_S
from ..errors import ValueRangeError

#: a field is refused when more than this share of its non-missing values is impossible
REFUSE_SHARE = 0.5

_HEIGHTS = (cv.WAVE_HS, cv.WIND_WAVE_HS, cv.SWELL_HS)
_PERIODS = (cv.WAVE_TM, cv.WIND_WAVE_TM, cv.SWELL_TM)
_VECTORS = ((cv.WIND_U, cv.WIND_V, WIND_SPEED_MAX_M_S),
            (cv.CURRENT_U, cv.CURRENT_V, CURRENT_SPEED_MAX_M_S))


@dataclass(frozen=True)
class OutlierLimit:
    """What is impossible for one field, in words (for reports)."""

    field: str
    rule: str


LIMITS = tuple(
    [OutlierLimit(n, f"Hs < 0 or > {HS_MAX_M:g} m") for n in _HEIGHTS]
    + [OutlierLimit(n, f"period <= 0 or > {PERIOD_MAX_S:g} s") for n in _PERIODS]
    + [OutlierLimit(f"{u}/{v}", f"speed > {lim:g} m/s") for u, v, lim in _VECTORS])


def _refuse_if_mostly(where: str, name: str, bad: int, valid: int, rule: str) -> None:
    if valid and bad > REFUSE_SHARE * valid:
        raise ValueRangeError(where, name, f"has {bad} of {valid} values impossible ({rule})",
                              "a forecast with mostly physical values")


def _within(a: np.ndarray, lo: float, hi: float, open_lo: bool = False) -> bool:
    """Whole field inside the limits (NaN skipped): two passes, no temporaries."""
    a_lo, a_hi = float(np.fmin.reduce(a, axis=None)), float(np.fmax.reduce(a, axis=None))
    if np.isnan(a_lo):
        return True  # all missing
    return (a_lo > lo if open_lo else a_lo >= lo) and a_hi <= hi


Impossible = tuple[tuple[str, ...], np.ndarray, str]  # (fields, mask, rule in words)


def _scalar_outliers(ds: xr.Dataset) -> Iterator[Impossible]:
    """Masks of impossible heights, periods and directions (fields with any only)."""
    for n in _HEIGHTS:
        if n in ds and not _within(ds[n].values, 0.0, HS_MAX_M):
            a = ds[n].values
            yield (n,), (a < 0.0) | (a > HS_MAX_M) | np.isinf(a), f"Hs < 0 or > {HS_MAX_M:g} m"
    for n in _PERIODS:
        if n in ds and not _within(ds[n].values, 0.0, PERIOD_MAX_S, open_lo=True):
            a = ds[n].values
            yield ((n,), (a <= 0.0) | (a > PERIOD_MAX_S) | np.isinf(a),
                   f"period <= 0 or > {PERIOD_MAX_S:g} s")
    for n in cv.DIRECTION_VARIABLES:
        if n in ds and not _within(ds[n].values, -1e30, 1e30):
            yield (n,), np.isinf(ds[n].values), "infinite direction"


def _vector_outliers(ds: xr.Dataset) -> Iterator[Impossible]:
    """Masks of impossible wind and current speeds (pairs with any only)."""
    for u, v, lim in _VECTORS:
        if u not in ds or v not in ds:
            continue
        a, b = ds[u].values, ds[v].values
        if _within(np.abs(a), 0.0, lim / np.sqrt(2.0)) and _within(
                np.abs(b), 0.0, lim / np.sqrt(2.0)):
            continue  # no component reaches lim / sqrt 2: no speed reaches lim
        speed2 = a.astype(np.float64) ** 2 + b.astype(np.float64) ** 2
        yield (u, v), ~(speed2 < lim * lim) & ~np.isnan(speed2), f"speed >= {lim:g} m/s"


def _mask(ds: xr.Dataset, where: str, counts: dict[str, int], names: tuple[str, ...],
          bad: np.ndarray, rule: str) -> None:
    """Set `bad` values of the fields `names` to NaN and count them (refuse mostly bad)."""
    valid = int(np.count_nonzero(~np.isnan(ds[names[0]].values)))
    n_bad = int(np.count_nonzero(bad))
    _refuse_if_mostly(where, "/".join(names), n_bad, valid, rule)
    if n_bad:
        for n in names:
            ds[n].values[bad] = np.nan
            counts[n] = counts.get(n, 0) + n_bad


def mask_outliers(ds: xr.Dataset, where: str) -> dict[str, int]:
    """Set impossible values of `ds`'s canonical fields to NaN in place; count per field.

    Raises ValueRangeError naming the file and field when most of a field is impossible.
    """
    counts: dict[str, int] = {}
    with np.errstate(invalid="ignore"):
        # each mask is made after the one before was applied (the generators are lazy)
        for names, bad, rule in itertools.chain(_scalar_outliers(ds), _vector_outliers(ds)):
            _mask(ds, where, counts, names, bad, rule)
    for n, k in counts.items():
        ds[n].attrs["masked_outliers"] = int(ds[n].attrs.get("masked_outliers", 0)) + k
    return counts


def masked_counts(ds: xr.Dataset) -> dict[str, int]:
    """Values masked as impossible per canonical field (from the variables' attributes)."""
    return {n: int(ds[n].attrs["masked_outliers"]) for n in cv.present_variables(ds)
            if int(ds[n].attrs.get("masked_outliers", 0))}
