"""One method's result in comparable numbers, plus the tables of the reference study's shape.

`MethodOutcome` is what the comparison keeps of each plan: TFOC, distance, arrival against the
RTA, land, whether RPM varied, compute time, evaluations and (3DDP, NSGA-II) the ETA-fuel
Pareto front. `comparison_table` prints tables 11/12 (each row as % of the first row);
`repeat_table` prints table 15 (runs, mean and standard deviation against the best known).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from datetime import UTC, datetime

import numpy as np


@dataclass(frozen=True)
class MethodOutcome:
    """Comparable summary of one method's plan on one scenario."""

    method: str
    label: str
    tfoc_t: float
    distance_nm: float
    eta_s: float
    rta_s: float
    land_crossings: int
    feasible: bool
    infeasible_reasons: tuple[str, ...]
    rpm_varied: bool
    rpm_mean: float
    compute_s: float
    route_evaluations: int
    track_lon_deg: np.ndarray = field(repr=False)
    track_lat_deg: np.ndarray = field(repr=False)
    leg_rpm: np.ndarray = field(repr=False)
    leg_sog_kn: np.ndarray = field(repr=False)
    leg_start_s: np.ndarray = field(repr=False)
    pareto_eta_s: np.ndarray | None = field(default=None, repr=False)
    pareto_fuel_t: np.ndarray | None = field(default=None, repr=False)

    @property
    def eta_minus_rta_h(self) -> float:
        return (self.eta_s - self.rta_s) / 3600.0

    def as_json(self) -> dict:
        """Plain-JSON summary (no per-leg arrays except the Pareto front)."""
        out = {
            "method": self.method,
            "label": self.label,
            "tfoc_t": round(self.tfoc_t, 3),
            "distance_nm": round(self.distance_nm, 2),
            "eta": _iso(self.eta_s),
            "eta_minus_rta_h": round(self.eta_minus_rta_h, 3),
            "land_crossings": int(self.land_crossings),
            "feasible": bool(self.feasible),
            "infeasible_reasons": list(self.infeasible_reasons),
            "rpm": "varied" if self.rpm_varied else round(self.rpm_mean, 2),
            "compute_s": round(self.compute_s, 3),
            "route_evaluations": int(self.route_evaluations),
        }
        if self.pareto_eta_s is not None and self.pareto_fuel_t is not None:
            out["pareto_front"] = [
                {"eta_minus_rta_h": round((e - self.rta_s) / 3600.0, 3), "tfoc_t": round(f, 3)}
                for e, f in zip(self.pareto_eta_s, self.pareto_fuel_t, strict=True)
            ]
        return out


def _iso(t_s: float) -> str:
    if not math.isfinite(t_s):
        return "none"
    return datetime.fromtimestamp(t_s, UTC).strftime("%Y-%m-%dT%H:%MZ")


def comparison_table(rows: list[MethodOutcome]) -> str:
    """Text table: method, TFOC (t, %), distance (NM, %), arrival vs RTA, land, RPM, time."""
    if not rows:
        return "(no methods)"
    ref_f, ref_d = rows[0].tfoc_t, rows[0].distance_nm
    head = (f"{'method':<28} {'TFOC [t]':>9} {'%':>6} {'dist [NM]':>10} {'%':>6} "
            f"{'arrival':>17} {'-RTA [h]':>8} {'RTA':>3} {'land':>4} {'RPM':>7} {'time [s]':>8}")
    lines = [head, "-" * len(head)]
    for r in rows:
        rpm = "varied" if r.rpm_varied else f"{r.rpm_mean:.1f}"
        lines.append(
            f"{r.label:<28} {r.tfoc_t:9.1f} {100 * r.tfoc_t / ref_f:5.1f}% "
            f"{r.distance_nm:10.0f} {100 * r.distance_nm / ref_d:5.1f}% "
            f"{_iso(r.eta_s):>17} {r.eta_minus_rta_h:8.1f} "
            f"{'O' if r.eta_s <= r.rta_s + 60 else 'X':>3} "
            f"{'O' if r.land_crossings == 0 else 'X':>4} {rpm:>7} {r.compute_s:8.2f}"
        )
    return "\n".join(lines)


@dataclass(frozen=True)
class RepeatRow:
    """Table 15 row: one algorithm's TFOC over repeated runs at an equal evaluation budget."""

    method: str
    label: str
    tfoc_t: tuple[float, ...]
    feasible: tuple[bool, ...]
    evaluations: int
    compute_s: float

    @property
    def mean_tfoc_t(self) -> float:
        return float(np.mean(self.tfoc_t))

    @property
    def std_tfoc_t(self) -> float:
        return float(np.std(self.tfoc_t, ddof=1)) if len(self.tfoc_t) > 1 else 0.0

    def as_json(self, best_known_t: float) -> dict:
        return {
            "method": self.method,
            "label": self.label,
            "tfoc_t": [round(v, 3) for v in self.tfoc_t],
            "feasible": list(self.feasible),
            "mean_tfoc_t": round(self.mean_tfoc_t, 3),
            "std_tfoc_t": round(self.std_tfoc_t, 3),
            "mean_pct_of_best_known": round(100 * self.mean_tfoc_t / best_known_t, 2),
            "std_pct_of_best_known": round(100 * self.std_tfoc_t / best_known_t, 2),
            "route_evaluations_per_run": self.evaluations,
            "compute_s_per_run": round(self.compute_s, 3),
        }


def repeat_table(rows: list[RepeatRow], best_known_t: float) -> str:
    """Text table in the shape of the reference study's table 15."""
    n = max((len(r.tfoc_t) for r in rows), default=0)
    runs = " ".join(f"{i + 1:>7}" for i in range(n))
    head = f"{'algorithm':<20} {runs} {'mean [t]':>9} {'%':>6} {'std [t]':>8} {'%':>5} {'evals':>7}"
    lines = [f"best-known optimum: {best_known_t:.1f} t", head, "-" * len(head)]
    for r in rows:
        vals = " ".join(f"{v:6.1f}{'' if ok else '*'}".rjust(7)
                        for v, ok in zip(r.tfoc_t, r.feasible, strict=True))
        lines.append(
            f"{r.label:<20} {vals} {r.mean_tfoc_t:9.1f} {100 * r.mean_tfoc_t / best_known_t:5.1f}% "
            f"{r.std_tfoc_t:8.1f} {100 * r.std_tfoc_t / best_known_t:4.1f}% {r.evaluations:7d}"
        )
    if any(not all(r.feasible) for r in rows):
        lines.append("* infeasible run: TFOC of its least-violating route")
    return "\n".join(lines)
