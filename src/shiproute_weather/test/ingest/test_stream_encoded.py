"""Block-wise encoding of a forecast file (`stream.load_encoded`): the same slices as
`load_slices`, each handed over with its final index and count, and the whole cycle never
held as float32 while it is encoded (the weather node's reload peak)."""

from __future__ import annotations

import tracemalloc
from dataclasses import replace
from pathlib import Path

import numpy as np
from shiproute_weather.errors import PackingError
from shiproute_weather.ingest.cycle_builder import CycleConfig
from shiproute_weather.ingest.stream import BLOCK_TIMES, load_encoded, load_slices
from shiproute_weather.wire.packing import pack_field
from shiproute_weather.wire.slices import FieldData, SliceData
from weather_fixtures import small_canonical, write_nc


def _packed(s: SliceData) -> SliceData:
    """The slice with its fields in 16-bit codes (what the node sends), +-inf kept float32."""
    fields = []
    for f in s.fields:
        try:
            fields.append(FieldData(f.name, f.units, f.direction_convention,
                                    pack_field(np.asarray(f.data), f.name)))
        except PackingError:
            fields.append(f)
    return replace(s, fields=tuple(fields))


def test_encoded_slices_equal_the_loaded_ones(tmp_path: Path) -> None:
    n = 2 * BLOCK_TIMES + 5  # three blocks, the last one short
    p = str(write_nc(small_canonical(n_time=n), tmp_path / "three_blocks.nc"))
    seen: list[tuple[int, int]] = []

    def keep(s: SliceData) -> SliceData:
        seen.append((s.slice_index, s.slice_count))
        return s

    info, encoded, notes = load_encoded(p, CycleConfig(), keep)
    info_ref, slices, notes_ref = load_slices(p, CycleConfig())
    assert seen == [(k, n) for k in range(n)]  # final index and count at encoding time
    assert info == info_ref and notes == notes_ref and info.slice_count == n
    for a, b in zip(encoded, slices, strict=True):
        assert a.valid_time_ns == b.valid_time_ns and a.grid == b.grid
        for fa, fb in zip(a.fields, b.fields, strict=True):
            np.testing.assert_array_equal(fa.data, fb.data)


def test_slice_cap_gives_the_count_at_encoding_time(tmp_path: Path) -> None:
    p = str(write_nc(small_canonical(n_time=BLOCK_TIMES + 4), tmp_path / "cap.nc"))
    seen: list[tuple[int, int]] = []
    info, out, _ = load_encoded(p, CycleConfig(max_slices=BLOCK_TIMES + 1),
                                lambda s: seen.append((s.slice_index, s.slice_count)) or s)
    assert info.slice_count == len(out) == BLOCK_TIMES + 1
    assert seen == [(k, BLOCK_TIMES + 1) for k in range(BLOCK_TIMES + 1)]


def _peak_bytes(fn) -> int:
    tracemalloc.start()
    try:
        result = fn()
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    del result
    return peak


def test_whole_cycle_is_never_held_as_float32(tmp_path: Path) -> None:
    """Packing block by block holds the packed cycle (2 of every 4 bytes) plus one block; the
    old order (all float32 slices, then packing) held the float32 cycle beside the packed one.
    Numpy reports its buffers to tracemalloc, so the peaks are the arrays' own bytes."""
    n = 8 * BLOCK_TIMES
    ds = small_canonical(n_time=n)
    float32_cycle = sum(ds[v].size * 4 for v in ds.data_vars)
    p = str(write_nc(ds, tmp_path / "eight_blocks.nc"))
    del ds
    cfg = CycleConfig()

    def old_order() -> list[SliceData]:
        _info, slices, _ = load_slices(p, cfg)
        return [_packed(s) for s in slices]

    def block_wise() -> list[SliceData]:
        return load_encoded(p, cfg, _packed)[1]

    old_peak = _peak_bytes(old_order)
    new_peak = _peak_bytes(block_wise)
    # the old peak holds the float32 cycle plus the packed one; the new one at most the packed
    # cycle and the working arrays of one block: half the float32 cycle is saved (0.4 allows
    # for the last block's slices still alive while the packed list completes)
    assert old_peak >= float32_cycle
    assert new_peak <= old_peak - 0.4 * float32_cycle, (new_peak, old_peak, float32_cycle)
    assert new_peak < float32_cycle
