"""What one published cycle costs on the wire and what keeps it bounded, in words for the node's
diagnostics (issue 19: say what 20 members cost per cycle and how it is bounded)."""

from __future__ import annotations

from ..wire.slices import CycleInfo
from .cycle_builder import CycleConfig


def wire_summary(info: CycleInfo, cycle_bytes: int, slice_bytes: int, encoding: str,
                 cfg: CycleConfig) -> str:
    """One line: members x valid times, bytes of field values per cycle and per slice, and the
    bounds that applied (encoding, box, member and time budget, slice size)."""
    n_t = info.slice_count // max(1, info.member_count)
    bounds = [f"{encoding} ({'2' if encoding == 'packed16' else '4'} B per value)"]
    if cfg.box is not None:
        b = cfg.box
        bounds.append(f"cut to {b.lat_min_deg:g}..{b.lat_max_deg:g} N, "
                      f"{b.lon_min_deg:g}..{b.lon_max_deg:g} E")
    else:
        bounds.append("no region or corridor cut (whole source grid)")
    bounds.append(f"<= {cfg.max_slices} slices (members x valid times; the slice history "
                  "depth)")
    if cfg.max_members > 0:
        bounds.append(f"<= {cfg.max_members} members")
    bounds.append(f"<= {cfg.max_slice_bytes} B of float32 per slice (else the grid is thinned)")
    return (f"{info.member_count} member(s) x {n_t} valid times = {info.slice_count} slices, "
            f"{cycle_bytes} B of field values per cycle ({slice_bytes} B per slice); bounded "
            f"by: {'; '.join(bounds)}")
