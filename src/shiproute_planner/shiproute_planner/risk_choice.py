"""The final choice of a risk-aware seed GA: the best candidate by the members' risk measure
whose route the exact evaluator and the dense coastline check confirm clear of land."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from shiproute_core.flags import FLAG_DEPTH, FLAG_LAND, FLAG_NO_GO_ZONE

from .ga.ranking import deb_order
from .geo.landmask import LandMask
from .geo.verify import land_crossings
from .route.encoding import gene_bounds
from .route.environment import Environment
from .route.evaluation import RouteEvaluation
from .route.generate import evaluate_genes
from .route.problem import RouteProblem

DENSE_CHECKS = 12  # best candidates (by risk) given the exact and dense land checks
TOP = 24  # best of the final population considered
# RPM scales of copies of the best: slower ones spend the members' ETA slack, faster ones
# repair a small lateness of the compiled evaluator's optimum
RPM_SCALES = (0.98, 0.99, 0.995, 1.005, 1.01, 1.02)
_GEOGRAPHY = np.uint32(FLAG_LAND | FLAG_DEPTH | FLAG_NO_GO_ZONE)


def risk_choice(p: RouteProblem, env: Environment, land: LandMask | None, pop: np.ndarray,
                evaluate_risk: Callable[[np.ndarray], RouteEvaluation]
                ) -> tuple[np.ndarray, RouteEvaluation]:
    """(genes, exact evaluation on the forecast's member mean) of the chosen candidate.

    Candidates (the best `TOP` and RPM-scaled copies of the best) are ranked by their
    risk-reduced violation and objective over the members; the first whose exact track on
    the members' mean is clear of land, shallow water and no-go zones (and, with a land
    mask, of the dense polygon check) wins; failing all, the best by risk (flagged)."""
    n = p.n_stages
    lo, hi = gene_bounds(p)
    bumped = np.repeat(pop[:1], len(RPM_SCALES), axis=0)
    bumped[:, n:] *= np.array(RPM_SCALES)[:, None]
    x = np.concatenate([pop[:TOP], np.clip(bumped, lo, hi)])
    ev = evaluate_risk(x)
    order = deb_order(ev.violation, ev.objective)
    first: tuple[int, RouteEvaluation] | None = None
    for k in order[:DENSE_CHECKS]:
        exact = evaluate_genes(p, env, land, x[k:k + 1])
        first = first or (int(k), exact)
        if exact.flags[0] & _GEOGRAPHY:
            continue
        if land is None or not land_crossings(exact.lon_deg[0], exact.lat_deg[0],
                                              port_clearance_m=0.0, contains=land.is_land):
            return x[k].copy(), exact
    assert first is not None
    return x[first[0]].copy(), first[1]
