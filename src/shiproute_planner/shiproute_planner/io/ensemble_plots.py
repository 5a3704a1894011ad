"""PNG of an ensemble plan: the fan of ETA against fuel over the members (P10/P50/P90 marked),
and the route over each member's storm: the contour where the member's highest Hs during the
voyage reaches the ship's limit (or 6 m without one), and each member's track of the Hs
maximum (the storm centre's wave field) day by day."""

from __future__ import annotations

from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import OutputError
from ..plan_types import RoutePlan
from .plots import save_figure

HS_VAR = "sea_surface_wave_significant_height"
DEFAULT_LEVEL_M = 6.0


def _hours(t_s: np.ndarray, t0_s: float) -> np.ndarray:
    return (np.asarray(t_s, dtype=float) - t0_s) / 3600.0


def _fan(ax: Any, plan: RoutePlan, block: dict[str, Any]) -> None:
    """ETA (h after departure) against fuel [t], one point per member, quantile lines."""
    fuel = np.asarray(block["fuel_t"]["per_member"], dtype=float)
    eta_h = _hours(np.asarray(block["eta_s"]["per_member"]), plan.departure_s)
    ax.scatter(fuel, eta_h, s=18, c="tab:blue", label=f"{block['members']} members")
    for q, style in (("p10", ":"), ("p50", "-"), ("p90", "--")):
        ax.axvline(block["fuel_t"][q], color="tab:orange", ls=style, lw=1,
                   label=f"fuel {q.upper()} {block['fuel_t'][q]:.0f} t")
        ax.axhline(_hours(np.array([block["eta_s"][q]]), plan.departure_s)[0], color="0.4",
                   ls=style, lw=1)
    ax.axhline(_hours(np.array([plan.rta_s]), plan.departure_s)[0], color="red", lw=1.2,
               label="RTA")
    ax.set_xlabel("fuel [t]")
    ax.set_ylabel("ETA [h after departure]")
    ax.set_title(f"members' outcomes (risk {block['risk_measure']}; P(Hs>limit) "
                 f"{block['p_hs_violation']:.2f}, P(late) {block['p_late']:.2f})", fontsize=9)
    ax.legend(fontsize=7, loc="upper right")
    ax.grid(alpha=0.3)


def _storms(ax: Any, plan: RoutePlan, forecast: Any, lon: np.ndarray) -> None:
    """Per member: Hs-limit contour of its voyage maximum and its daily Hs-maximum track."""
    hs = forecast[HS_VAR]
    t0 = np.datetime64(datetime.fromtimestamp(plan.departure_s, UTC).replace(tzinfo=None))
    t1 = np.datetime64(datetime.fromtimestamp(plan.eta_s, UTC).replace(tzinfo=None))
    hs = hs.sel(time=slice(t0, t1))
    if hs.sizes.get("time", 0) == 0:
        return
    centre = 0.5 * (lon.min() + lon.max())
    glon = forecast["longitude"].values
    glon = centre + (glon - centre + 180.0) % 360.0 - 180.0
    order = np.argsort(glon)
    glat = forecast["latitude"].values
    level = plan.vessel_max_wave_m if np.isfinite(plan.vessel_max_wave_m) else DEFAULT_LEVEL_M
    from matplotlib import colormaps

    colours = colormaps["tab20"]
    members = hs.sizes.get("member", 1)
    for k in range(members):
        one = hs.isel(member=k) if "member" in hs.dims else hs
        values = one.values  # (time, lat, lon)
        peak = np.nanmax(values, axis=0)[:, order]
        if np.nanmax(peak) >= level:
            ax.contour(glon[order], glat, peak, levels=[level], colors=[colours(k % 20)],
                       linewidths=0.8)
        daily = values[:: max(1, values.shape[0] // 16)]
        flat = np.nanargmax(np.nan_to_num(daily, nan=-1.0).reshape(daily.shape[0], -1), axis=1)
        i, j = np.unravel_index(flat, daily.shape[1:])
        ax.plot(glon[j], glat[i], ".", ms=3, color=colours(k % 20))
    ax.plot(lon, plan.track()[1], "r.-", lw=2, label=f"plan {plan.total_fuel_t:.0f} t")
    ax.set_title(f"route over the members' storms: Hs >= {level:g} m during the voyage "
                 "(contours) and each member's Hs-maximum track (dots)", fontsize=9)
    ax.set_xlabel("longitude [deg E, continuous]")
    ax.set_ylabel("latitude [deg N]")
    ax.legend(fontsize=7, loc="lower left")
    ax.set_xlim(lon.min() - 10, lon.max() + 10)
    ax.set_ylim(max(plan.track()[1].min() - 10, -90), min(plan.track()[1].max() + 12, 90))


def write_ensemble_png(plan: RoutePlan, path: str | Path, forecast: Any = None) -> Path:
    """Write the ensemble plot of a plan with an `ensemble` block (the forecast dataset with
    its members for the storm panel; without it only the fan)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    block = plan.extra.get("ensemble")
    if not block:
        raise OutputError("the plan has no ensemble statement to plot")
    lon, _, _ = plan.track()
    fig = plt.figure(figsize=(11, 10))
    _fan(fig.add_axes((0.08, 0.06, 0.84, 0.32)), plan, block)
    if forecast is not None and HS_VAR in forecast:
        _storms(fig.add_axes((0.08, 0.46, 0.84, 0.5)), plan, forecast, lon)
    return save_figure(fig, path)
