"""The plan flags defined once in shiproute_core equal the FLAG_* constants of RoutePlan.msg."""

from __future__ import annotations

import re
from pathlib import Path

from shiproute_core import flags

MSG = Path(__file__).resolve().parents[2] / "shiproute_msgs" / "msg" / "RoutePlan.msg"
_CONST = re.compile(r"^\s*uint32\s+(FLAG_[A-Z_]+)\s*=\s*(\d+)", re.MULTILINE)


def _msg_flags() -> dict[str, int]:
    return {name: int(value) for name, value in _CONST.findall(MSG.read_text())}


def _core_flags() -> dict[str, int]:
    return {k: v for k, v in vars(flags).items() if k.startswith("FLAG_") and isinstance(v, int)}


def test_every_interface_flag_is_defined_with_the_same_bit() -> None:
    msg, core = _msg_flags(), _core_flags()
    assert len(msg) >= 15, f"parsed only {len(msg)} FLAG_* constants from {MSG}"
    assert {k: core.get(k) for k in msg} == msg


def test_core_has_no_flag_the_interface_lacks_except_internal_ones() -> None:
    extra = set(_core_flags()) - set(_msg_flags())
    assert extra == set(flags.PLANNER_INTERNAL_FLAGS)


def test_flags_are_distinct_single_bits_with_names() -> None:
    values = list(_core_flags().values())
    assert len(set(values)) == len(values)
    assert all(v > 0 and v & (v - 1) == 0 for v in values)
    assert set(flags.FLAG_NAMES) == set(values)
