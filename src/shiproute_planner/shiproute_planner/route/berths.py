"""The zone round a berth that land tests leave to the pilot, one figure for the route check,
the final repair and the coastal passages (a passage must be off land wherever the check
will test it)."""

from __future__ import annotations

#: round a berth (along the track from it) land is not tested: harbour basins and the snap of a
#: gazetteer position onto water are the pilot's
BERTH_RADIUS_M = 3000.0
