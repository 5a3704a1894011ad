"""Fit the learned model: held-out split by time, ensembles of scikit-learn MLPs, metrics.

Each member is an `MLPRegressor` with one hidden ReLU layer (reference 003), trained with
L-BFGS (a quasi-Newton method; 003 used Levenberg-Marquardt, which scikit-learn does not
offer) on a bootstrap resample of the training segments, seeded per member, so a run is
reproducible. The test set is the latest voyages (at least ``test_fraction`` of the
segments): the model is judged on later voyages than it learned from, as it will be used.
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass

import numpy as np

from ..ship.spec import ShipSpec
from .errors import TrainingDataError
from .features import (
    FEATURES,
    SEGMENT_COLUMNS,
    feature_matrix,
    physics_prior,
    sea_of,
    ship_identity,
)
from .model import LearnedModel, Network


@dataclass(frozen=True)
class TrainConfig:
    """Ensemble size, network widths, regularisation, split and data minimums."""

    members: int = 5
    rpm_hidden: int = 16
    fuel_hidden: int = 16
    alpha: float = 0.1  # L2 penalty on the weights (z-scored inputs and target)
    max_iter: int = 300
    test_fraction: float = 0.2
    min_segments: int = 150  # clean segments the whole data set must give
    min_test_segments: int = 20
    fallback_std: float = 1.0
    seed: int = 0


def split_by_time(time_s: np.ndarray, voyage: np.ndarray,
                  test_fraction: float) -> tuple[np.ndarray, np.ndarray]:
    """(train, test) index arrays: whole latest voyages until >= test_fraction of segments."""
    order = sorted(np.unique(voyage), key=lambda v: float(np.min(time_s[voyage == v])))
    need = test_fraction * time_s.size
    test_voyages: list = []
    count = 0
    for v in reversed(order[1:]):  # the first voyage always trains
        if count >= need:
            break
        test_voyages.append(v)
        count += int(np.sum(voyage == v))
    is_test = np.isin(voyage, test_voyages)
    if count < need or not np.any(~is_test):  # one voyage only: split it at a time
        cut = np.quantile(time_s, 1.0 - test_fraction)
        is_test = time_s >= cut
    return np.flatnonzero(~is_test), np.flatnonzero(is_test)


def rel_errors(pred: np.ndarray, meas: np.ndarray) -> dict[str, float]:
    """Mean and 95th-percentile relative error [%]."""
    e = np.abs(pred - meas) / np.abs(meas) * 100.0
    return {"mre_pct": float(np.mean(e)), "p95_pct": float(np.percentile(e, 95))}


def _fit(x: np.ndarray, y: np.ndarray, hidden: int, cfg: TrainConfig, salt: int) -> Network:
    from sklearn.exceptions import ConvergenceWarning
    from sklearn.neural_network import MLPRegressor
    from threadpoolctl import threadpool_limits

    y_mean, y_std = float(np.mean(y)), float(np.std(y)) or 1.0
    yz = (y - y_mean) / y_std
    rng = np.random.default_rng([cfg.seed, salt])
    w0, b0, w1, b1 = [], [], [], []
    for k in range(cfg.members):
        idx = rng.integers(0, x.shape[0], x.shape[0]) if cfg.members > 1 else np.arange(x.shape[0])
        net = MLPRegressor(hidden_layer_sizes=(hidden,), activation="relu", solver="lbfgs",
                           alpha=cfg.alpha, max_iter=cfg.max_iter,
                           random_state=int(cfg.seed * 1000 + salt * 100 + k))
        # one BLAS thread: these matrices are small, and threads on a shared machine made a
        # fit 15x slower
        with warnings.catch_warnings(), threadpool_limits(1):
            warnings.simplefilter("ignore", ConvergenceWarning)  # lbfgs stops at max_iter
            net.fit(x[idx], yz[idx])
        w0.append(net.coefs_[0])
        b0.append(net.intercepts_[0])
        w1.append(net.coefs_[1][:, 0])
        b1.append(float(net.intercepts_[1][0]))
    return Network(np.array(w0), np.array(b0), np.array(w1), np.array(b1), y_mean, y_std)


def train(ship: ShipSpec, segments: dict[str, np.ndarray], cfg: TrainConfig = TrainConfig(),
          cleaning: dict | None = None) -> LearnedModel:
    """Train on clean segment means (columns `features.SEGMENT_COLUMNS`); metrics go into the
    model's ``report`` (``metrics``: learned and physics-prior errors on the held-out voyages)."""
    missing = [c for c in SEGMENT_COLUMNS if c not in segments]
    if missing:
        raise TrainingDataError(f"segment table lacks columns {missing}")
    n = int(np.asarray(segments["time_s"]).size)
    if n < cfg.min_segments:
        raise TrainingDataError(
            f"only {n} clean segments; training needs at least {cfg.min_segments} "
            f"(about {cfg.min_segments * 10 / 60:.0f} h of steady sailing in ~10-minute "
            "segments); record more voyages or check why the cleaning dropped them")
    t0 = time.perf_counter()
    s = {k: np.asarray(v, dtype=float) for k, v in segments.items()}
    sea = sea_of(s)
    x = feature_matrix(s["stw_kn"], s["heading_deg"], s["draft_fore_m"], s["draft_aft_m"], sea)
    rpm0, fuel0 = physics_prior(ship, s["stw_kn"], s["heading_deg"], sea, s["draft_fore_m"],
                                s["draft_aft_m"])
    y_rpm, y_fuel = np.log(s["rpm"] / rpm0), np.log(s["fuel_t_per_h"] / fuel0)
    tr, te = split_by_time(s["time_s"], s["voyage"], cfg.test_fraction)
    if te.size < cfg.min_test_segments:
        raise TrainingDataError(f"only {te.size} held-out segments of later voyages; "
                                f"need at least {cfg.min_test_segments}")
    x_mean, x_std = x[tr].mean(axis=0), x[tr].std(axis=0)
    x_std = np.where(x_std > 1e-6, x_std, 1.0)  # a constant input (e.g. one draft) stays 0
    xz = (x - x_mean) / x_std
    rpm_net = _fit(xz[tr], y_rpm[tr], cfg.rpm_hidden, cfg, 1)
    fuel_net = _fit(xz[tr], y_fuel[tr], cfg.fuel_hidden, cfg, 2)
    latest = s["voyage"][tr][np.argmax(s["time_s"][tr])]
    ref = tr[s["voyage"][tr] == latest]
    model = LearnedModel(
        ship.name, ship_identity(ship), x_mean, x_std, x[tr].min(axis=0), x[tr].max(axis=0),
        rpm_net, fuel_net, float(np.median(s["draft_fore_m"][ref])),
        float(np.median(s["draft_aft_m"][ref])), cfg.fallback_std)
    train_s = time.perf_counter() - t0
    r = model.residuals(x[te])
    rpm_err = rel_errors(rpm0[te] * np.exp(r["rpm"]), s["rpm"][te])
    fuel_err = rel_errors(fuel0[te] * np.exp(r["fuel"]), s["fuel_t_per_h"][te])
    metrics = {
        "train_segments": int(tr.size), "test_segments": int(te.size),
        "test_voyages": sorted({int(v) for v in s["voyage"][te]}),
        "train_s": train_s,
        "fuel_mre_pct": fuel_err["mre_pct"], "fuel_p95_pct": fuel_err["p95_pct"],
        "rpm_mre_pct": rpm_err["mre_pct"], "rpm_p95_pct": rpm_err["p95_pct"],
        "physics_fuel_mre_pct": rel_errors(fuel0[te], s["fuel_t_per_h"][te])["mre_pct"],
        "physics_rpm_mre_pct": rel_errors(rpm0[te], s["rpm"][te])["mre_pct"],
        "fuel_rel_std_median_pct": float(np.median(r["fuel_std"]) * 100.0),
        "rpm_rel_std_median_pct": float(np.median(r["rpm_std"]) * 100.0),
        "test_outside_training_range": int(np.sum(r["weight"] < 1.0 - 1e-9)),
    }
    ranges = {f: [float(a), float(b)] for f, a, b in
              zip(FEATURES, model.x_lo, model.x_hi, strict=True)}
    report = {"metrics": metrics, "training_ranges": ranges, "cleaning": cleaning or {},
              "config": {k: getattr(cfg, k) for k in cfg.__dataclass_fields__}}
    return LearnedModel(**{**model.__dict__, "report": report})
