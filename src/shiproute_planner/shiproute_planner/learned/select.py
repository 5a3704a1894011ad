"""The planner's ship-model choice: ``physics``, ``kwon``, ``profile:FILE.nc``, ``learned:FILE.nc``.

``physics`` (the default, and what an empty choice means unless the ship file names another
with ``performance_model``) is the tabulated physics model. ``learned`` is tabulated the same
way (`tables`), and ``kwon`` and ``profile`` through `ship.tabulate`, so every choice keeps
the GA's compiled fast path. Every choice but the default adds a line to the plan's warnings
(with how closely the tables follow the model), and a learned model says how many legs left
its training range.
"""

from __future__ import annotations

import functools
from pathlib import Path
from typing import Any

import numpy as np

from ..ship.fast import fast_model
from ..ship.spec import ShipSpec
from ..ship.tabulate import calibration_note, tabulated_model
from .errors import LearnError, ModelFileError
from .features import feature_matrix
from .model import LearnedModel

CHOICES = "physics, kwon, profile:FILE.nc or learned:FILE.nc"


def resolve_model(ship: ShipSpec, choice: str = "") -> tuple[Any, tuple[str, ...]]:
    """(performance model, warnings) for ``choice`` ("" = the ship file's entry or physics)."""
    choice = (choice or ship.performance_model or "physics").strip()
    kind, _, path = choice.partition(":")
    if kind == "physics" and not path:
        return fast_model(ship), ()
    if kind == "kwon" and not path:
        fm = _tabulated(ship, "kwon", "")
        return fm, ("ship model: Kwon (2008) speed loss on the ship file's calm-water curve",
                    calibration_note(fm))
    if kind in ("profile", "learned") and path:
        if not Path(path).is_file():
            raise ModelFileError(f"{kind} model file {path} does not exist")
        if kind == "profile":
            fm = _tabulated(ship, path, str(Path(path).stat().st_mtime_ns))
            return fm, (f"ship model: performance profile {path} (interpolated)",
                        calibration_note(fm))
        learned, fm = _learned(ship, path, Path(path).stat().st_mtime_ns)
        m = learned.report.get("metrics", {})
        return fm, (
            f"ship model: learned from records ({path}; {m.get('train_segments', '?')} clean "
            f"segments; held-out fuel MRE {m.get('fuel_mre_pct', float('nan')):.1f} %, RPM "
            f"MRE {m.get('rpm_mre_pct', float('nan')):.2f} %) at drafts "
            f"{learned.reference_draft_fore_m:.2f}/{learned.reference_draft_aft_m:.2f} m "
            "fore/aft of the latest training voyage",)
    raise LearnError(f"ship model {choice!r}: use {CHOICES}")


@functools.lru_cache(maxsize=8)
def _learned(ship: ShipSpec, path: str, mtime_ns: int) -> tuple[LearnedModel, Any]:
    """Model file read and tabulated once per (ship, file version): re-plans reuse it."""
    from .tables import learned_fast_model

    del mtime_ns  # part of the cache key only
    learned = LearnedModel.load(path)
    return learned, learned_fast_model(ship, learned, source=path)


@functools.lru_cache(maxsize=8)
def _tabulated(ship: ShipSpec, what: str, version: str) -> Any:
    """Kwon's model (``what`` "kwon") or the profile file ``what`` tabulated for the fast
    path, once per (ship, file version): re-plans reuse it."""
    del version  # part of the cache key only
    if what == "kwon":
        from ..ship.kwon import KwonModel

        return tabulated_model(ship, KwonModel(ship), "Kwon (2008)")
    from ..ship.profile import ProfileModel

    return tabulated_model(ship, ProfileModel(ship, what), f"profile {Path(what).name}")


def plan_warnings(model: Any, plan: Any) -> tuple[str, ...]:
    """For a learned model: its ensemble spread along ``plan`` and how many legs left the
    training range (the learned correction fades to the physics model there: in the planner's
    tables exactly in speed, in weather as fitted factors on the physics added resistance)."""
    learned: LearnedModel | None = getattr(model, "learned", None)
    wps = plan.waypoints[:-1]
    if learned is None or not wps:
        return ()
    from ..ship.seastate import SeaState

    def arr(name: str) -> np.ndarray:
        return np.array([getattr(w, name) for w in wps], dtype=float)

    wind_from = np.radians(arr("wind_from_deg"))
    ws = arr("wind_speed_m_s")
    hs = arr("hs_m")
    period = np.full(hs.size, float(learned.x_mean[-1]))
    sea = SeaState.from_arrays(
        wind_u_m_s=-ws * np.sin(wind_from), wind_v_m_s=-ws * np.cos(wind_from),
        wind_wave_hs_m=hs, wind_wave_from_deg=arr("wave_from_deg"), wind_wave_period_s=period)
    stw = arr("stw_kn")
    good = np.isfinite(stw) & np.isfinite(hs) & np.isfinite(ws)
    if not np.any(good):
        return ()
    x = feature_matrix(stw[good], arr("heading_deg")[good], learned.reference_draft_fore_m,
                       learned.reference_draft_aft_m, sea.take(np.flatnonzero(good)))
    r = learned.residuals(x)
    w = r["weight"]
    notes = [f"learned ship model: ensemble spread along the plan "
             f"{100 * np.median(r['fuel_std']):.1f} % of fuel rate, "
             f"{100 * np.median(r['rpm_std']):.2f} % of RPM (median over legs)"]
    out = int(np.sum(w < 1.0 - 1e-9))
    if out:
        lo, hi = learned.x_lo, learned.x_hi
        notes.append(
            f"learned ship model: {out} of {int(good.sum())} legs outside its training range "
            f"(STW {lo[0]:.1f}-{hi[0]:.1f} kn, Hs <= {hi[5]:.1f} m, wind <= {hi[3]:.0f} m/s); "
            "there it falls back towards the ship file's physics model "
            f"({int(np.sum(w == 0.0))} legs fully physics)")
    return tuple(notes)
