"""Comparison figures: all routes over the wave field with RPM/speed profiles, and Pareto fronts."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .outcome import MethodOutcome

HS_VAR = "sea_surface_wave_significant_height"


def _hs_field(ds, time_s: float):
    """(lon, lat, Hs) of the forecast at the valid time nearest `time_s`, or None."""
    if ds is None or HS_VAR not in getattr(ds, "data_vars", {}):
        return None
    t = np.datetime64(int(time_s), "s").astype("datetime64[ns]")
    field = ds[HS_VAR].sel(time=t, method="nearest")
    return ds["longitude"].values, ds["latitude"].values, field.values


def plot_comparison(outcomes: list[MethodOutcome], path: Path, ds=None, title: str = "") -> Path:
    """Map of every route over Hs at mid-voyage, and RPM and SOG along longitude."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(13, 9))
    ax_map = fig.add_subplot(2, 1, 1)
    ax_rpm = fig.add_subplot(2, 2, 3)
    ax_sog = fig.add_subplot(2, 2, 4)
    mid_s = 0.5 * (outcomes[0].leg_start_s[0] + outcomes[0].rta_s) if outcomes else 0.0
    field = _hs_field(ds, mid_s)
    all_lon = np.concatenate([o.track_lon_deg for o in outcomes])
    all_lat = np.concatenate([o.track_lat_deg for o in outcomes])
    if field is not None:
        lon, lat, hs = field
        pcm = ax_map.pcolormesh(lon, lat, hs, shading="auto", cmap="Blues", vmin=0)
        fig.colorbar(pcm, ax=ax_map, label="Hs [m] at mid-voyage")
    colors = plt.cm.tab20(np.linspace(0, 1, max(len(outcomes), 2)))
    for o, c in zip(outcomes, colors, strict=False):
        ax_map.plot(o.track_lon_deg, o.track_lat_deg, "-", color=c, lw=1.4,
                    label=f"{o.label} ({o.tfoc_t:.0f} t)")
        mid_lon = 0.5 * (o.track_lon_deg[:-1] + o.track_lon_deg[1:])
        ax_rpm.step(mid_lon, o.leg_rpm, where="mid", color=c, lw=1.0)
        ax_sog.plot(mid_lon, o.leg_sog_kn, color=c, lw=1.0)
    pad = 3.0
    ax_map.set_xlim(all_lon.min() - pad, all_lon.max() + pad)
    ax_map.set_ylim(all_lat.min() - pad, all_lat.max() + pad)
    ax_map.set_xlabel("longitude [deg E, continuous]")
    ax_map.set_ylabel("latitude [deg N]")
    ax_map.legend(fontsize=7, loc="lower left", ncol=2)
    ax_map.set_title(title or "routes of every method")
    for ax, label in ((ax_rpm, "engine RPM [1/min]"), (ax_sog, "speed over ground [kn]")):
        ax.set_xlabel("longitude [deg E]")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def plot_pareto(outcomes: list[MethodOutcome], path: Path) -> Path | None:
    """ETA-vs-fuel Pareto fronts of the methods that have one (3DDP, two-objective NSGA-II)."""
    fronts = [(o, o.pareto_eta_s, o.pareto_fuel_t) for o in outcomes
              if o.pareto_eta_s is not None and o.pareto_fuel_t is not None
              and o.pareto_eta_s.size]
    if not fronts:
        return None
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 5))
    for o, eta_s, fuel_t in fronts:
        rel_h = (eta_s - o.rta_s) / 3600.0
        ax.plot(rel_h, fuel_t, "o-", ms=3, lw=1, label=o.label)
        ax.plot([(o.eta_s - o.rta_s) / 3600.0], [o.tfoc_t], "k*", ms=10)
    ax.axvline(0.0, color="r", ls="--", lw=1, label="RTA")
    ax.set_xlabel("ETA - RTA [h]")
    ax.set_ylabel("TFOC [t]")
    ax.set_title("ETA-fuel Pareto fronts (star: route chosen for the RTA)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
