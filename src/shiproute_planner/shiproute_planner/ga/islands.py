"""Seed GA islands: seeds grouped by the side of the great circle they take, searched apart,
then merged into one population.

A storm across the great circle splits good routes into basins (pass north of it, south of
it, or through it early/late). One population converges on whichever basin its first
feasible individual found; islands keep each basin alive until the merge, and the merged
population then refines the best of them (thesis sec. 5.2's seed GA, run per seed group).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from .loop import GAConfig, SeedGA
from .ranking import deb_order


def cross_track_rad(lon_deg: np.ndarray, lat_deg: np.ndarray, dep: tuple[float, float],
                    arr: tuple[float, float]) -> np.ndarray:
    """Mean signed angular distance [rad] of each track's nodes (pop, k) from the great
    circle dep -> arr (positive to the left of the direction of travel)."""

    def unit(lon: np.ndarray, lat: np.ndarray) -> np.ndarray:
        lo, la = np.radians(lon), np.radians(lat)
        return np.stack([np.cos(la) * np.cos(lo), np.cos(la) * np.sin(lo), np.sin(la)], -1)

    a = unit(np.array(dep[0]), np.array(dep[1]))
    b = unit(np.array(arr[0]), np.array(arr[1]))
    normal = np.cross(a, b)
    normal /= max(float(np.linalg.norm(normal)), 1e-12)
    return np.arcsin(np.clip(unit(lon_deg, lat_deg) @ normal, -1.0, 1.0)).mean(axis=-1)


class IslandGA:
    """Several `SeedGA`s on seed groups, asked and told as one; `merge` joins them.

    Seeds arrive best first with their cross-track offsets; they are split into `n_islands`
    groups by offset (south to north of the great circle, or right to left), each group
    keeping its quality order. Until `merge`, `ask` concatenates the islands' offspring and
    `tell` hands each island its share; afterwards it is a single `SeedGA`. Both are
    `loop.AskTellGA`s to the planning loop."""

    def __init__(self, lower: np.ndarray, upper: np.ndarray, n_stages: int, config: GAConfig,
                 rng: np.random.Generator, seeds: np.ndarray, offsets: np.ndarray,
                 n_islands: int = 3) -> None:
        self.lo, self.hi, self.n, self.cfg, self.rng = lower, upper, n_stages, config, rng
        k = max(1, min(n_islands, len(seeds)))
        sub = dataclasses.replace(config, pop_size=max(16, config.pop_size // 2),
                                  offspring=max(16, config.offspring // 2))
        if k == 1:
            self.islands = [SeedGA(lower, upper, n_stages, config, rng, seeds)]
        else:
            rank = np.argsort(np.argsort(offsets, kind="stable"), kind="stable")
            group = rank * k // len(seeds)
            self.islands = [SeedGA(lower, upper, n_stages, sub, rng, seeds[group == g])
                            for g in range(k)]
        self._sizes: list[int] = []
        self.merged = len(self.islands) == 1

    def ask(self) -> np.ndarray:
        """Offspring of every island, concatenated."""
        parts = [isl.ask() for isl in self.islands]
        self._sizes = [len(x) for x in parts]
        return np.concatenate(parts)

    def parts(self) -> list[tuple[slice, SeedGA]]:
        """Each island's rows in the last `ask` result."""
        out, start = [], 0
        for isl, size in zip(self.islands, self._sizes, strict=True):
            out.append((slice(start, start + size), isl))
            start += size
        return out

    def tell(self, x: np.ndarray, violation: np.ndarray, objective: np.ndarray) -> None:
        """Give each island its evaluated offspring (the first rows of the last `ask` when
        an evaluation budget cut it short)."""
        for sl, isl in self.parts():
            sl = slice(min(sl.start, len(x)), min(sl.stop, len(x)))
            if sl.stop > sl.start:
                isl.tell(x[sl], violation[sl], objective[sl])

    def inject(self, x: np.ndarray, violation: np.ndarray, objective: np.ndarray,
               spent: int = 0) -> None:
        """Merge genes evaluated outside the loop into the island holding the best."""
        cand = [isl.best for isl in self.islands]
        order = deb_order(np.array([c[1] for c in cand]), np.array([c[2] for c in cand]))
        self.islands[int(order[0])].inject(x, violation, objective, spent)

    def merge(self) -> None:
        """Join the islands: one population of the best of all (Deb order), same config."""
        if self.merged or self.pop is None:  # nothing evaluated yet: nothing to merge
            return
        pop = np.concatenate([isl.pop for isl in self.islands])
        v = np.concatenate([isl.pop_v for isl in self.islands])
        f = np.concatenate([isl.pop_f for isl in self.islands])
        keep = deb_order(v, f)[: self.cfg.pop_size]
        ga = SeedGA(self.lo, self.hi, self.n, self.cfg, self.rng, pop[keep])
        ga.pop, ga.pop_v, ga.pop_f = pop[keep], v[keep], f[keep]
        ga.generation = self.generation
        ga.evaluations = self.evaluations
        ga.best_history = [(float(v[keep[0]]), float(f[keep[0]]))]
        self.islands = [ga]
        self.merged = True

    @property
    def pop(self) -> np.ndarray | None:
        """Current population(s), best island first after a merge; None before `tell`."""
        if any(isl.pop is None for isl in self.islands):
            return None
        if self.merged:
            return self.islands[0].pop
        pop = np.concatenate([isl.pop for isl in self.islands])
        v = np.concatenate([isl.pop_v for isl in self.islands])
        f = np.concatenate([isl.pop_f for isl in self.islands])
        return pop[deb_order(v, f)]

    @property
    def best(self) -> tuple[np.ndarray, float, float]:
        """Best genes over all islands, their violation and objective."""
        cand = [isl.best for isl in self.islands]
        order = deb_order(np.array([c[1] for c in cand]), np.array([c[2] for c in cand]))
        return cand[int(order[0])]

    @property
    def generation(self) -> int:
        return max(isl.generation for isl in self.islands)

    @property
    def evaluations(self) -> int:
        return sum(isl.evaluations for isl in self.islands)

    def stalled(self, generations: int, rel_tol: float = 1e-4) -> bool:
        """Stall of the merged population (islands never count as stalled)."""
        return self.merged and self.islands[0].stalled(generations, rel_tol)
