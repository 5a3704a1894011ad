"""Local refinement of the GA's best route: projected finite-difference descent.

Close to the optimum a GA wastes most offspring on moves far larger than the remaining
improvement. For a fixed route shape the fuel of a voyage is nearly convex in the stage
speeds (fuel per distance ~ speed^2) and the arrival time is smooth in them, so a few
gradient steps that keep the ETA on the RTA close what random mutation leaves: one batch
evaluates a forward difference per gene, a second a line search along the fuel gradient
projected onto constant ETA (plus a first-order correction of the ETA onto its target).
Every candidate goes through the caller's evaluator, so constraints (land, depth, sea
state, RTA) are judged exactly as in the GA: the result is never worse than the start by
Deb's rules.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .ranking import deb_order, is_better


@dataclass(frozen=True)
class PolishConfig:
    """Step sizes and effort of the refinement."""

    # forward-difference steps: large enough to see through the half-precision forecast and
    # the stage discretisation, small against the GA's mutations (0.7 rpm, 1 deg)
    rpm_step: float = 0.5  # [rpm]
    heading_step_deg: float = 0.2  # [deg]
    with_headings: bool = True  # descend on the heading genes too (route shape)
    line_steps: tuple[float, ...] = (0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0)
    eta_margin_s: float = 120.0  # aim this far before the RTA (the exact evaluator differs)
    max_rounds: int = 40
    modes: int = 0  # > 0: smooth moves of this many modes (route and RPM) instead of genes


@dataclass(frozen=True)
class PolishResult:
    """Refined genes, their violation and objective, and the effort spent."""

    x: np.ndarray
    violation: float
    objective: float
    evaluations: int
    rounds: int


EvaluateFn = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray]]


def polish(x0: np.ndarray, evaluate: EvaluateFn, lo: np.ndarray, hi: np.ndarray,
           n_stages: int, rta_s: float, deadline_s: float, max_evaluations: int = 0,
           config: PolishConfig | None = None) -> PolishResult:
    """Projected descent from genes `x0` until `deadline_s` (perf_counter), the evaluation
    budget, `max_rounds` or no further gain. `evaluate(x)` returns (violation, objective,
    eta_s) arrays of the rows of `x`."""
    cfg = config or PolishConfig()
    moves = (smooth_moves(n_stages, cfg.modes, cfg.heading_step_deg, cfg.rpm_step)
             if cfg.modes else gene_moves(n_stages, cfg))
    x = np.clip(np.asarray(x0, dtype=float), lo, hi)
    v, f, eta = (float(a[0]) for a in evaluate(x[None, :]))
    spent, rounds, scale = 1, 0, 1.0
    target = rta_s - cfg.eta_margin_s
    alphas0 = np.asarray(cfg.line_steps)
    while rounds < cfg.max_rounds and time.perf_counter() < deadline_s:
        if max_evaluations and spent + len(moves) + alphas0.size > max_evaluations:
            break
        rounds += 1
        # forward differences along each move (objective and ETA per unit move)
        pv, pf, pe = evaluate(np.clip(x[None, :] + moves, lo, hi))
        spent += len(moves)
        ok = (pv <= v) & np.isfinite(pf) & np.isfinite(pe)
        g_f = np.where(ok, pf - f, 0.0)
        g_t = np.where(ok, pe - eta, 0.0)
        direction = descent_direction(g_f, g_t, eta - target)
        if not np.any(direction):
            break
        alphas = scale * alphas0
        cand = np.clip(x[None, :] + alphas[:, None] * (direction @ moves)[None, :], lo, hi)
        cv, cf, ce = evaluate(cand)
        spent += len(cand)
        k = int(deb_order(cv, cf)[0])
        if is_better(float(cv[k]), float(cf[k]), v, f):
            x, v, f, eta = cand[k], float(cv[k]), float(cf[k]), float(ce[k])
            # next line search centred on the step that won
            scale = float(np.clip(alphas[k] / 4.0, 0.05, 20.0))
        else:
            scale *= 0.25
            if scale < 0.02:
                break
    return PolishResult(x, v, f, spent, rounds)


def gene_moves(n_stages: int, cfg: PolishConfig) -> np.ndarray:
    """One move per gene (the heading genes only `with_headings`), one difference step long."""
    n = n_stages
    genes = np.arange(0 if cfg.with_headings else n, 2 * n + 1)
    moves = np.zeros((genes.size, 2 * n + 1))
    moves[np.arange(genes.size), genes] = np.where(genes < n, cfg.heading_step_deg,
                                                   cfg.rpm_step)
    return moves


def smooth_moves(n_stages: int, modes: int, heading_step_deg: float,
                 rpm_step: float) -> np.ndarray:
    """Smooth whole-route moves: RPM profiles cos(pi m s / n) over the stages (m = 0 is the
    common level) and sideways bulges sin(pi m k / n) of the nodes that rejoin the track at
    the ends, as heading genes (the bulge's first difference as absolute heading offsets,
    made relative). Few moves see through the stage-by-stage roughness of the weather and
    cost one evaluation each."""
    n = n_stages
    s = np.arange(n + 1) / max(n, 1)
    out = []
    for m in range(modes + 1):
        mv = np.zeros(2 * n + 1)
        mv[n:] = rpm_step * np.cos(np.pi * m * s)
        out.append(mv)
    for m in range(1, modes + 1) if n > 1 else ():
        bulge = heading_step_deg * np.sin(np.pi * m * s)
        offset = np.diff(bulge)  # absolute heading offsets of stages 0..n-1
        mv = np.zeros(2 * n + 1)
        mv[0] = offset[0]
        mv[1:n] = np.diff(offset)
        out.append(mv)
    return np.array(out)


def descent_direction(g_f: np.ndarray, g_t: np.ndarray, eta_excess_s: float) -> np.ndarray:
    """Step (in units of the genes' difference steps) that lowers the objective at constant
    ETA, plus the first-order move of the ETA by -`eta_excess_s`; normalised so the largest
    gene moves one unit when the objective part dominates."""
    tt = float(g_t @ g_t)
    if tt > 0:
        along = g_f - (float(g_f @ g_t) / tt) * g_t
        fix = -(eta_excess_s / tt) * g_t
    else:
        along, fix = g_f.copy(), np.zeros_like(g_f)
    top = float(np.max(np.abs(along))) if along.size else 0.0
    d = -along / top if top > 0 else np.zeros_like(g_f)
    return d + fix
