"""What the planner node reads and states once at start: depth grids and the seed pool."""

from __future__ import annotations

from pathlib import Path


def load_depth_grids(files: list[str], with_default: bool) -> str:
    """Read the depth grids now (they are cached per process), so the first plan's budget is
    spent planning; returns what was loaded, raises `PlannerError` for a bad grid."""
    from ..geo.depth import load_bathymetry

    bathy = load_bathymetry(files, with_default=with_default)
    return "depth: " + ("no bathymetry grid (depth not checked)" if bathy is None
                        else "bathymetry grids loaded")


def seed_pool_statement(directory: str) -> str:
    """What the persisted seed pool holds, so a restart visibly continues from it; raises
    whatever a damaged pool raises."""
    from ..ga.pool import POOL_FILE, SeedPool

    n = len(SeedPool(directory))
    return f"seed pool: {n} seed(s) in {Path(directory) / POOL_FILE}"
