"""The search clock's allowance for one-off coastline tile builds.

The first plans in a region on a machine build the full-resolution distance tiles their
candidates meet (`geo.fine_distance`, ~15-30 ms each, kept in the data directory). Charged
to the search, fifty of them left a 3-s re-plan no generation; excused from the GA's clock
(up to `ALLOWANCE_SHARE` of the budget) the plan runs longer once and says so.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .geo.fine_distance import tile_builds

ALLOWANCE_SHARE = 1.0  # at most this share of the budget is added to the search's clock


@dataclass
class TileAllowance:
    """Tiles built and seconds spent building them since the search started, the seconds
    excused from its clock capped at `cap_s`."""

    cap_s: float
    start: tuple[int, float] = field(default_factory=tile_builds)

    def spent(self) -> tuple[int, float]:
        """(tiles, seconds) built since the start."""
        tiles, seconds = tile_builds()
        return tiles - self.start[0], max(seconds - self.start[1], 0.0)

    def excused_s(self) -> float:
        """Seconds the search's deadline moves back for the tiles built so far."""
        return min(self.spent()[1], self.cap_s)

    def statement(self) -> tuple[str, ...]:
        """The plan's warning when tiles were built during the search (none otherwise)."""
        tiles, seconds = self.spent()
        if tiles == 0:
            return ()
        excused = min(seconds, self.cap_s)
        return (f"search: built {tiles} full-resolution coastline tile(s) in {seconds:.2f} s "
                f"(first plans in this region on this machine; kept for later plans); "
                f"the search's clock was extended by {excused:.2f} s for them",)


def tile_allowance(budget_s: float) -> TileAllowance:
    """The allowance of a search with `budget_s` of wall time."""
    return TileAllowance(ALLOWANCE_SHARE * budget_s)
