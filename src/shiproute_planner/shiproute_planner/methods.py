"""Registry of planning methods: name -> function(MethodContext) -> MethodResult.

Every method plans one leg (`RouteProblem`) with the shared evaluator and returns the chosen
route as a single-row `RouteEvaluation`: the seed GA (`seed_ga`), the constant-RPM baseline
(`great_circle`) and the baselines of `baselines.registry` (isochrone, A*, 3DDP, pymoo).
Other code may add methods with `register_method`.
"""

from __future__ import annotations

from .errors import UnknownMethodError
from .method_context import MethodContext, MethodFn, MethodResult, compute_baseline
from .seed_ga import seed_ga_method

_METHODS: dict[str, MethodFn] = {}
_BASELINES_LOADED = False


def great_circle_method(ctx: MethodContext) -> MethodResult:
    """Constant RPM meeting the RTA on the great circle (sea lane if the circle hits land)."""
    b = ctx.baseline or compute_baseline(ctx.problem, ctx.env, ctx.land)
    return MethodResult(b.evaluation, b.name, 0, 1)


def register_method(name: str, fn: MethodFn) -> None:
    """Add or replace a planning method."""
    _METHODS[name] = fn


def get_method(name: str) -> MethodFn:
    """The method registered as `name`."""
    _load_baselines()
    try:
        return _METHODS[name]
    except KeyError:
        raise UnknownMethodError(
            f"planning method {name!r} is unknown; available: {', '.join(sorted(_METHODS))}"
        ) from None


def method_names() -> list[str]:
    """Registered method names."""
    _load_baselines()
    return sorted(_METHODS)


def _load_baselines() -> None:
    """Register the baseline methods on first use (their modules load pymoo and the graph
    searches, which a plan with the seed GA does not need)."""
    global _BASELINES_LOADED
    if _BASELINES_LOADED:
        return
    _BASELINES_LOADED = True
    try:
        from .baselines.registry import baseline_methods
    except ImportError:  # an optional dependency of the baselines missing: the rest still plan
        return
    for name, fn in baseline_methods().items():
        _METHODS.setdefault(name, fn)


register_method("seed_ga", seed_ga_method)
register_method("great_circle", great_circle_method)
