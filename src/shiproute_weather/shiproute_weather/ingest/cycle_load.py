"""The weather node's one load path: files (or multi-model members) to encoded slices.

One NetCDF file, deterministic or an ensemble, is streamed member by member and block by block
(`stream.load_encoded`: the float32 cycle never exists); anything else (GRIB, several files
combined, multi-model members, a wind-only file whose waves are grown) is loaded whole by
`cycle_builder.build_cycle` and each slice is encoded and dropped in turn.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TypeVar

from ..wire.slices import CycleInfo, SliceData
from .cycle_builder import CycleConfig, build_cycle
from .stream import load_encoded, streamable

T = TypeVar("T")


def load_cycle(paths: Sequence[str], cfg: CycleConfig, members: Sequence[Sequence[str]],
               encode: Callable[[SliceData], T]) -> tuple[CycleInfo, list[T], list[str], str]:
    """(cycle announcement, encoded slices, notes, "streamed" | "whole") of one load."""
    if not members and streamable(list(paths), cfg):
        info, out, notes = load_encoded(paths[0], cfg, encode)
        return info, out, notes, "streamed"
    info, slices, notes = build_cycle(paths, cfg, members)
    encoded: list[T] = []
    for k in range(len(slices)):
        s, slices[k] = slices[k], None  # type: ignore[call-overload]  # freed once encoded
        encoded.append(encode(s))
        del s
    return info, encoded, notes, "whole"
