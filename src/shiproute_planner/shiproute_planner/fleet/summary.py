"""Fleet summary: one CSV row per voyage (Parquet too when pyarrow is installed), the rows
skipped with their line and reason, and a plot of fuel saved per vessel, ETA margins and
constraint flags."""

from __future__ import annotations

import csv
import importlib.util
import math
from collections import Counter, defaultdict
from pathlib import Path
from typing import Any

from .voyages import RowError

COLUMNS = (
    "voyage_id", "group", "vessel", "line", "status", "reason", "ship", "model", "method",
    "objective", "from", "to", "via", "departure", "rta", "window_start", "forecast", "budget",
    "seed", "feasible", "flags", "warnings", "fuel_t", "baseline_fuel_t", "baseline_feasible",
    "fuel_saved_t", "fuel_saved_pct", "eta", "eta_margin_h", "distance_nm", "evaluations",
    "plan_s", "best_candidate", "already_planned", "worker", "out_dir", "key",
)


def mark_best_candidates(records: list[dict[str, Any]]) -> None:
    """Per row with candidate departures/RTAs (same group and forecast): flag the feasible
    candidate with the least fuel as `best_candidate`."""
    groups: dict[tuple, list[dict]] = defaultdict(list)
    for r in records:
        if r.get("status") == "planned":
            groups[(r.get("group"), r.get("forecast"))].append(r)
    for members in groups.values():
        ok = [r for r in members if r.get("feasible")] or members
        best = min(ok, key=lambda r: r.get("fuel_t", math.inf))
        for r in members:
            r["best_candidate"] = r is best if len(members) > 1 else ""


def comparable(r: dict[str, Any]) -> bool:
    """A planned voyage whose saving means something: plan and baseline both feasible (an
    infeasible baseline, e.g. across land, is cheap for the wrong reason), one candidate
    per row (the best), finite fuel."""
    return (r.get("status") == "planned" and bool(r.get("feasible"))
            and bool(r.get("baseline_feasible")) and r.get("best_candidate") in ("", None, True)
            and math.isfinite(float(r.get("fuel_saved_t") or math.nan)))


def skipped_records(errors: list[RowError]) -> list[dict[str, Any]]:
    """Rows of the voyages file that were not planned, as summary records."""
    return [{"voyage_id": e.voyage, "line": e.line, "status": "invalid",
             "reason": f"line {e.line}: {e.reason}"} for e in errors]


def write_summary(records: list[dict[str, Any]], out_dir: str | Path) -> dict[str, Path]:
    """fleet_summary.csv (+ .parquet with pyarrow) and fleet_summary.png in out_dir."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    files = {"csv": out / "fleet_summary.csv"}
    tmp = files["csv"].with_suffix(".csv.tmp")
    with tmp.open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=COLUMNS, extrasaction="ignore")
        w.writeheader()
        for r in records:
            w.writerow({k: _cell(r.get(k)) for k in COLUMNS})
    tmp.replace(files["csv"])
    if importlib.util.find_spec("pyarrow") is not None:
        import pyarrow as pa
        import pyarrow.parquet as pq

        table = pa.table({k: [_cell(r.get(k)) for r in records] for k in COLUMNS})
        files["parquet"] = out / "fleet_summary.parquet"
        pq.write_table(table, files["parquet"])
    files["png"] = write_plot(records, out / "fleet_summary.png")
    return files


def _cell(v: Any) -> Any:
    if isinstance(v, float):
        return "" if not math.isfinite(v) else round(v, 6)
    return "" if v is None else v


def write_plot(records: list[dict[str, Any]], path: Path) -> Path:
    """Three panels: fuel saved against the constant-RPM baseline per vessel (t), ETA margin
    per voyage (h before the RTA; negative = late), and how many voyages carry each flag."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    planned = [r for r in records if r.get("status") == "planned"]
    saved: dict[str, float] = defaultdict(float)
    for r in planned:
        if comparable(r):
            saved[str(r.get("vessel"))] += float(r["fuel_saved_t"])
    flags: Counter[str] = Counter()
    for r in records:
        if r.get("status") != "planned":
            flags[str(r.get("status"))] += 1
            continue
        for f in filter(None, str(r.get("flags") or "").split(";")):
            flags[f] += 1
        if r.get("feasible"):
            flags["all constraints met"] += 1
    fig, axes = plt.subplots(1, 3, figsize=(16, min(max(4.0, 0.16 * max(len(planned), 10)), 60)),
                             gridspec_kw={"width_ratios": [1.2, 1.2, 1.0]})
    names = sorted(saved)
    axes[0].barh(names, [saved[n] for n in names],
                 color=["tab:green" if saved[n] >= 0 else "tab:red" for n in names])
    axes[0].set_xlabel("fuel saved vs constant-RPM baseline (t; plan and baseline feasible)")
    axes[0].set_title("fuel saved per vessel")
    ids = [str(r["voyage_id"]) for r in planned]
    margins = [float(r.get("eta_margin_h") or 0.0) for r in planned]
    axes[1].barh(ids, margins, color=["tab:blue" if m >= 0 else "tab:red" for m in margins])
    axes[1].axvline(0.0, color="k", lw=0.8)
    axes[1].set_xlabel("ETA margin: hours before the RTA (negative = late)")
    axes[1].set_title("ETA margins")
    labels = sorted(flags)
    axes[2].barh(labels, [flags[k] for k in labels], color="tab:orange")
    axes[2].set_xlabel("voyages")
    axes[2].set_title("flags")
    for ax in axes:
        ax.tick_params(axis="y", labelsize=7)
    fig.suptitle(f"fleet: {len(planned)} planned, "
                 f"{sum(1 for r in records if r.get('status') != 'planned')} not planned")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return path
