"""ISO 19030-style cleaning of voyage records into steady ~10-minute segments (reference 003).

Steps, each counted in the report (records dropped per rule, in this order):
1. ``incomplete``: a record without time, position, SOG, COG, heading, RPM, fuel rate or
   drafts; ``no_met``: no forecast covers it; ``not_under_way``: RPM <= 0 or SOG below
   ``min_sog_kn``; ``stuck_value``: RPM, fuel rate or SOG repeating exactly over
   ``stuck_records`` or more records (a frozen sensor; real readings carry noise).
2. Relative directions of wind and waves to the bow (`features`, when training).
3. Consecutive records are cut into segments of ``segment_s`` (10 min; a pause longer than a
   quarter of it, or a new voyage, starts a new one); ``short_segment``: < ``min_records``.
4. Per segment, mean (circular for angles, 003 eq. 4-5) and the dispersion sigma =
   sqrt(mean((d - mean)^2)) (003 eq. 6-8, which 003 calls the standard error of the mean).
   ISO 19030-2 filters where 003 is silent: ``shallow_water`` when the depth is known
   (h < max(3 sqrt(B T), 2.75 V^2 / g), ITTC/ISO 15016), ``rudder`` (mean |rudder angle| >
   ``max_rudder_deg``, when a rudder column exists) and ``heading_change`` (heading sigma >
   ``max_heading_std_deg``: turns and manoeuvres when the rudder is not recorded).
5. 003's thresholds: ``rpm_std`` (RPM sigma > 3 rpm) and ``sog_std`` (SOG sigma > 0.5 kn).
6. ``chauvenet``: within each remaining segment a record is an outlier in a quantity when
   N erfc(|d - mean| / (sigma sqrt 2)) < 0.5 (003 eq. 9-10); outliers are removed and the
   segment means recomputed; ``short_after_chauvenet``: fewer than ``min_records`` left.
7. z-scoring of the inputs happens in training (the scaling is stored in the model file).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import erfc
from shiproute_core.units import M_S_PER_KNOT

from .records import Records

G = 9.80665
ANGLES = ("heading_deg", "cog_deg")
CHAUVENET_FIELDS = ("sog_kn", "stw_kn", "shaft_rpm", "fuel_rate_t_per_h", "heading_deg",
                    "draft_fore_m", "draft_aft_m")
RECORD_RULES = ("incomplete", "no_met", "not_under_way", "stuck_value")
SEGMENT_RULES = ("short_segment", "shallow_water", "rudder", "heading_change", "rpm_std",
                 "sog_std")


@dataclass(frozen=True)
class CleaningConfig:
    """Thresholds of the cleaning (defaults: reference 003 and ISO 19030-2)."""

    segment_s: float = 600.0
    min_records: int = 5
    max_rpm_std: float = 3.0
    max_sog_std_kn: float = 0.5
    max_heading_std_deg: float = 3.0
    max_rudder_deg: float = 5.0
    min_sog_kn: float = 3.0
    stuck_records: int = 5
    breadth_m: float = float("nan")  # ship breadth for the shallow-water criterion


def _circ_mean_deg(a: np.ndarray, seg: np.ndarray, n: int) -> np.ndarray:
    r = np.radians(a)
    s = np.bincount(seg, np.sin(r), n)
    c = np.bincount(seg, np.cos(r), n)
    return np.degrees(np.arctan2(s, c)) % 360.0


def _stats(x: np.ndarray, seg: np.ndarray, n: int, angle: bool) -> tuple[np.ndarray, ...]:
    """Per-segment mean, per-record deviation |d - mean| and per-segment sigma (003 eq. 4-8)."""
    counts = np.bincount(seg, minlength=n).astype(float)
    if angle:
        mean = _circ_mean_deg(x, seg, n)
        r = np.abs(x - mean[seg]) % 360.0
        dev = np.where(r > 180.0, 360.0 - r, r)
    else:
        mean = np.bincount(seg, x, n) / np.maximum(counts, 1)
        dev = np.abs(x - mean[seg])
    sigma = np.sqrt(np.bincount(seg, dev**2, n) / np.maximum(counts, 1))
    return mean, dev, sigma


def _stuck(x: np.ndarray, run: int) -> np.ndarray:
    """True where x repeats exactly over >= run consecutive records."""
    same = np.concatenate([[False], x[1:] == x[:-1]])
    start = np.flatnonzero(~same)
    lengths = np.diff(np.concatenate([start, [x.size]]))
    run_len = np.repeat(lengths, lengths)
    return run_len >= run


def _segments(t: np.ndarray, voyage: np.ndarray, cfg: CleaningConfig) -> np.ndarray:
    """Segment id per record (records in time order)."""
    seg = np.empty(t.size, dtype=np.int64)
    k, start = -1, -np.inf
    for i in range(t.size):
        if (t[i] - start >= cfg.segment_s or i == 0 or voyage[i] != voyage[i - 1]
                or t[i] - t[i - 1] > 0.25 * cfg.segment_s):
            k += 1
            start = t[i]
        seg[i] = k
    return seg


def clean(records: Records, met: dict[str, np.ndarray],
          cfg: CleaningConfig = CleaningConfig()) -> tuple[dict[str, np.ndarray], dict]:
    """(segment table with `SEGMENT_COLUMNS` and extras, report) of records + met."""
    c = {**records.columns, **met}
    n0 = len(records)
    dropped = dict.fromkeys((*RECORD_RULES, *SEGMENT_RULES, "chauvenet", "short_after_chauvenet"),
                            0)
    seg_dropped = dict.fromkeys((*SEGMENT_RULES, "short_after_chauvenet"), 0)
    keep = np.ones(n0, dtype=bool)

    def drop(rule: str, bad: np.ndarray) -> None:
        hit = bad & keep
        dropped[rule] += int(hit.sum())
        keep[hit] = False

    req = ("time_s", "latitude_deg", "longitude_deg", "sog_kn", "cog_deg", "heading_deg",
           "shaft_rpm", "fuel_rate_t_per_h", "draft_fore_m", "draft_aft_m")
    drop("incomplete", ~np.all([np.isfinite(c[k]) for k in req], axis=0))
    drop("no_met", ~np.all([np.isfinite(met[k]) for k in met], axis=0))
    drop("not_under_way", ~((c["shaft_rpm"] > 0) & (c["sog_kn"] >= cfg.min_sog_kn)))
    stuck = np.zeros(n0, dtype=bool)
    for k in ("shaft_rpm", "fuel_rate_t_per_h", "sog_kn"):
        stuck |= _stuck(np.nan_to_num(c[k], nan=-1.0), cfg.stuck_records)
    drop("stuck_value", stuck)
    # speed through water: the log, else SOG minus the forecast current
    from_log = np.isfinite(c["stw_kn"])
    cog = np.radians(c["cog_deg"])
    e = c["sog_kn"] * M_S_PER_KNOT * np.sin(cog) - c["current_u_m_s"]
    nn = c["sog_kn"] * M_S_PER_KNOT * np.cos(cog) - c["current_v_m_s"]
    stw = np.where(from_log, c["stw_kn"], np.hypot(e, nn) / M_S_PER_KNOT)
    c = {**c, "stw_kn": stw}
    idx = np.flatnonzero(keep)
    r = {k: np.asarray(v)[idx] for k, v in c.items()}
    seg = _segments(r["time_s"], r["voyage"], cfg)
    n = int(seg.max()) + 1 if seg.size else 0
    ok = np.ones(n, dtype=bool)

    def seg_drop(rule: str, bad: np.ndarray) -> None:
        hit = bad & ok
        seg_dropped[rule] += int(hit.sum())
        dropped[rule] += int(np.isin(seg, np.flatnonzero(hit)).sum())
        ok[hit] = False

    counts = np.bincount(seg, minlength=n)
    seg_drop("short_segment", counts < cfg.min_records)
    not_applied = []
    depth = r["water_depth_m"]
    if np.any(np.isfinite(depth)) and np.isfinite(cfg.breadth_m):
        t_mean = 0.5 * (r["draft_fore_m"] + r["draft_aft_m"])
        v = r["stw_kn"] * M_S_PER_KNOT
        limit = np.maximum(3.0 * np.sqrt(cfg.breadth_m * t_mean), 2.75 * v**2 / G)
        shallow = np.bincount(seg, np.isfinite(depth) & (depth < limit), n) > 0
        seg_drop("shallow_water", shallow)
    else:
        not_applied.append("shallow_water (no water depth in the records)")
    rudder = r["rudder_angle_deg"]
    if np.any(np.isfinite(rudder)):
        m_abs = np.bincount(seg, np.nan_to_num(np.abs(rudder)), n) / np.maximum(counts, 1)
        seg_drop("rudder", m_abs > cfg.max_rudder_deg)
    else:
        not_applied.append("rudder (no rudder angle in the records; heading_change applies)")
    seg_drop("heading_change", _stats(r["heading_deg"], seg, n, True)[2] > cfg.max_heading_std_deg)
    seg_drop("rpm_std", _stats(r["shaft_rpm"], seg, n, False)[2] > cfg.max_rpm_std)
    seg_drop("sog_std", _stats(r["sog_kn"], seg, n, False)[2] > cfg.max_sog_std_kn)
    # Chauvenet within the steady segments
    live = ok[seg]
    outlier = np.zeros(seg.size, dtype=bool)
    for k in CHAUVENET_FIELDS:
        _, dev, sigma = _stats(r[k], seg, n, k in ANGLES)
        s = sigma[seg]
        p = np.where(s > 0, erfc(dev / np.where(s > 0, s, 1.0) / np.sqrt(2.0)), 1.0)
        outlier |= counts[seg] * p < 0.5
    outlier &= live
    dropped["chauvenet"] = int(outlier.sum())
    rest = live & ~outlier
    counts2 = np.bincount(seg[rest], minlength=n)
    short2 = ok & (counts2 < cfg.min_records)
    seg_dropped["short_after_chauvenet"] = int(short2.sum())
    dropped["short_after_chauvenet"] = int(counts2[short2].sum())
    ok &= ~short2
    final = rest & ok[seg]
    table = _means(r, seg[final], final, n)
    report = {
        "records_in": n0, "records_kept": int(final.sum()),
        "clean_segments": int(table["time_s"].size),
        "dropped_by_rule": dropped, "segments_dropped_by_rule": seg_dropped,
        "rules_not_applied": not_applied,
        "stw_source": {"log": int(from_log[keep].sum()),
                       "sog_minus_forecast_current": int((~from_log[keep]).sum())},
        "config": {k: getattr(cfg, k) for k in cfg.__dataclass_fields__},
    }
    return table, report


def _means(r: dict[str, np.ndarray], seg: np.ndarray, mask: np.ndarray,
           n: int) -> dict[str, np.ndarray]:
    """Segment means of the kept records (segments renumbered densely)."""
    from shiproute_planner.learned.features import SEA_COLUMNS

    used, dense = np.unique(seg, return_inverse=True)
    m = used.size
    counts = np.bincount(dense, minlength=m).astype(float)
    out: dict[str, np.ndarray] = {}
    names = {"shaft_rpm": "rpm", "fuel_rate_t_per_h": "fuel_t_per_h"}
    for k in ("time_s", "voyage", "latitude_deg", "longitude_deg", "sog_kn", "stw_kn",
              "shaft_rpm", "fuel_rate_t_per_h", "draft_fore_m", "draft_aft_m", *SEA_COLUMNS,
              "heading_deg", "cog_deg"):
        x = r[k][mask]
        if k in ANGLES or k.endswith("_from_deg") or k == "longitude_deg":
            out[names.get(k, k)] = _circ_mean_deg(x, dense, m)
        else:
            out[names.get(k, k)] = np.bincount(dense, x, m) / counts
    out["n_records"] = counts
    del n
    return out
