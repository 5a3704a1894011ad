"""Drift of the ship from a model over time: the ISO 19030 performance indicator.

Per clean segment: the speed loss, 100 (V_measured - V_expected) / V_expected, V_expected the
model's speed through water at the measured RPM in the segment's weather (ISO 19030-2's
percentage speed loss, with RPM standing in for the delivered power the records lack), and
the excess fuel, 100 (F_measured / F_expected - 1), F_expected the model's fuel rate at the
measured speed. Both are averaged per day (the evaluation period) and a linear trend per
30 days is fitted: a fouling hull shows a growing speed loss and excess fuel.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from shiproute_core.units import M_S_PER_KNOT

DAY_S = 86400.0


def drift_table(segments: dict[str, np.ndarray], model: Any,
                learned: Any = None) -> dict[str, np.ndarray]:
    """Per-segment speed loss and excess fuel [%] against ``model`` (a PerformanceModel; with
    ``learned`` the fuel expectation comes from the learned model directly)."""
    from shiproute_planner.learned.features import sea_of

    s = segments
    sea = sea_of(s)
    if learned is not None:  # the learned model at each segment's own drafts
        v_exp = _learned_speed_kn(learned, model.ship, s, sea)
    else:
        v_exp = model.evaluate(s["rpm"], s["heading_deg"], sea).stw_m_s / M_S_PER_KNOT
    if learned is not None:
        fuel_exp = learned.predict(model.ship, s["stw_kn"], s["heading_deg"], s["draft_fore_m"],
                                   s["draft_aft_m"], sea).fuel_t_per_h
    else:
        stw_m_s = np.maximum(s["stw_kn"], 0.5) * M_S_PER_KNOT
        rpm = model.rpm_for_speed(stw_m_s, s["heading_deg"], sea)
        fuel_exp = model.evaluate(rpm, s["heading_deg"], sea).fuel_t_per_h
    return {"time_s": s["time_s"], "speed_loss_pct": 100.0 * (s["stw_kn"] - v_exp) / v_exp,
            "excess_fuel_pct": 100.0 * (s["fuel_t_per_h"] / fuel_exp - 1.0)}


def _learned_speed_kn(learned: Any, ship: Any, s: dict[str, np.ndarray], sea: Any) -> np.ndarray:
    """Speed through water at which the learned model needs the measured RPM (bisection;
    the learned RPM rises with speed)."""
    lo = np.full(s["rpm"].size, 2.0)
    hi = np.full(s["rpm"].size, 30.0)
    for _ in range(30):
        mid = 0.5 * (lo + hi)
        rpm = learned.predict(ship, mid, s["heading_deg"], s["draft_fore_m"], s["draft_aft_m"],
                              sea).rpm
        low = rpm < s["rpm"]
        lo = np.where(low, mid, lo)
        hi = np.where(low, hi, mid)
    return 0.5 * (lo + hi)


def daily(table: dict[str, np.ndarray]) -> dict[str, Any]:
    """Daily means and the 30-day trend of both indicators."""
    day = np.floor(table["time_s"] / DAY_S)
    days = np.unique(day)
    rows = []
    for d in days:
        m = day == d
        rows.append({"day_utc": np.datetime_as_string(np.datetime64(int(d * DAY_S), "s"), "D"),
                     "segments": int(m.sum()),
                     "speed_loss_pct": float(np.mean(table["speed_loss_pct"][m])),
                     "excess_fuel_pct": float(np.mean(table["excess_fuel_pct"][m]))})
    trend = {}
    t_days = (table["time_s"] - table["time_s"].min()) / DAY_S
    for k in ("speed_loss_pct", "excess_fuel_pct"):
        slope = (float(np.polyfit(t_days, table[k], 1)[0]) * 30.0
                 if np.ptp(t_days) > 0.5 else float("nan"))
        trend[k.replace("_pct", "_trend_pct_per_30d")] = slope
        trend[k.replace("_pct", "_mean_pct")] = float(np.mean(table[k]))
    return {"days": rows, **trend}


def plot(table: dict[str, np.ndarray], summary: dict[str, Any], path: str | Path,
         title: str) -> None:
    """Two panels over time: segments (dots) and daily means (line) of both indicators."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = table["time_s"].astype("datetime64[s]")
    fig, axes = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    days = np.array([np.datetime64(r["day_utc"]) + np.timedelta64(12, "h")
                     for r in summary["days"]])
    for ax, k, label in ((axes[0], "speed_loss_pct", "speed loss [%]"),
                         (axes[1], "excess_fuel_pct", "excess fuel [%]")):
        ax.plot(t, table[k], ".", ms=2, alpha=0.4, label="10-min segments")
        ax.plot(days, [r[k] for r in summary["days"]], "-o", label="daily mean")
        ax.axhline(0.0, color="k", lw=0.8)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0].legend(loc="best")
    axes[0].set_title(title)
    axes[1].set_xlabel("time (UTC)")
    fig.autofmt_xdate()
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
