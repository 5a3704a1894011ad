"""PNG of a plan: route (and baseline) over the significant wave height at the ship's time,
and profiles of RPM, speed over ground and fuel rate along the voyage."""

from __future__ import annotations

from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import OutputError
from ..geo.gshhg import load_land_polygons
from ..plan_types import RoutePlan

HS_VAR = "sea_surface_wave_significant_height"


def write_png(plan: RoutePlan, path: str | Path, forecast: Any = None,
              time_s: float | None = None) -> Path:
    """Write the plot; `forecast` is a canonical xarray Dataset (or None: no Hs field)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    lon, lat, t = plan.track()
    t_map = plan.departure_s if time_s is None else time_s
    fig = plt.figure(figsize=(11, 9))
    ax = fig.add_axes((0.07, 0.42, 0.86, 0.54))
    centre = 0.5 * (lon.min() + lon.max())
    if forecast is not None and HS_VAR in forecast:
        when = np.datetime64(datetime.fromtimestamp(t_map, UTC).replace(tzinfo=None), "ns")
        hs = forecast[HS_VAR].sel(time=when, method="nearest")
        if "member" in hs.dims:  # an ensemble: the members' mean (the ensemble PNG has each)
            hs = hs.mean("member")
        glon = forecast["longitude"].values
        glon = centre + (glon - centre + 180.0) % 360.0 - 180.0
        order = np.argsort(glon)
        mesh = ax.pcolormesh(glon[order], forecast["latitude"].values,
                             hs.values[:, order], cmap="viridis", shading="auto", vmin=0)
        fig.colorbar(mesh, ax=ax, label="Hs [m]", fraction=0.03)
    poly = load_land_polygons("l")
    lon_min, lon_max = lon.min() - 10, lon.max() + 10
    lat_min, lat_max = max(lat.min() - 8, -90), min(lat.max() + 8, 90)
    for i in range(len(poly)):
        b = poly.bounds[i]
        if b[3] < lat_min or b[1] > lat_max:
            continue
        ring = poly.ring(i)
        for shift in (-360.0, 0.0, 360.0):
            x = ring[:, 0] + shift
            if x.max() < lon_min or x.min() > lon_max:
                continue
            ax.fill(x, ring[:, 1], color="0.75", lw=0)
    if plan.baseline_track:
        b = np.array(plan.baseline_track)
        blon = np.unwrap(b[:, 1], period=360.0)
        blon += np.round((lon[0] - blon[0]) / 360.0) * 360.0
        ax.plot(blon, b[:, 0], "w--", lw=1.5, label=f"baseline ({plan.baseline_method}) "
                f"{plan.baseline_fuel_t:.1f} t")
    ax.plot(lon, lat, "r.-", lw=2, label=f"{plan.method} {plan.total_fuel_t:.1f} t")
    ax.set_xlim(lon_min, lon_max)
    ax.set_ylim(lat_min, lat_max)
    ax.set_xlabel("longitude [deg E, continuous]")
    ax.set_ylabel("latitude [deg N]")
    when_txt = datetime.fromtimestamp(t_map, UTC).strftime("%Y-%m-%d %H:%MZ")
    ax.set_title(f"{' -> '.join(plan.ports)}  (Hs at {when_txt})")
    ax.legend(loc="lower left", fontsize=8)
    hours = (t[:-1] - t[0]) / 3600.0
    w = plan.waypoints[:-1]
    for row, (vals, label) in enumerate((
        ([x.shaft_rpm for x in w], "RPM"),
        ([x.sog_kn for x in w], "SOG [kn]"),
        # a rate, not a per-leg total: approach legs along the lane last up to days
        ([24.0 * 3600.0 * x.leg_fuel_t / max(x.leg_duration_s, 1.0) for x in w],
         "fuel rate [t/day]"),
    )):
        a = fig.add_axes((0.07 + row * 0.31, 0.06, 0.25, 0.27))
        a.step(hours, vals, where="post")
        a.set_xlabel("time since departure [h]")
        a.set_title(label, fontsize=9)
        a.grid(alpha=0.3)
    return save_figure(fig, path)


def save_figure(fig: Any, path: str | Path, dpi: int = 90) -> Path:
    """Write `fig` as PNG to `path` and close it (OutputError naming the path on failure)."""
    import matplotlib.pyplot as plt

    try:
        fig.savefig(path, dpi=dpi)
    except OSError as exc:
        raise OutputError(f"cannot write plot {path}: {exc}") from exc
    finally:
        plt.close(fig)
    return Path(path)
