"""Run a benchmark script registered in entry-point group `shiproute.bench` (`bench <name>`)."""

from __future__ import annotations

from shiproute_bringup.dispatch import dispatch

GROUP = "shiproute.bench"


def main(argv: list[str]) -> int:
    """``shiproute bench <name> [args...]`` (benchmarks print one JSON object with --json)."""
    return dispatch("shiproute bench", GROUP, argv, what="benchmark")
