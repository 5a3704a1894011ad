"""How every `shiproute bench NAME` prints its figures: one JSON object on one line with
`--json` (what scripts and the closing notes read), else one aligned `name: value` line each."""

from __future__ import annotations

import json
from collections.abc import Collection, Mapping


def print_figures(figures: Mapping[str, object], as_json: bool,
                  leave_out: Collection[str] = ()) -> None:
    """Print a benchmark's figures; `leave_out` names figures too long for a line of text
    (the JSON form always has them all)."""
    if as_json:
        print(json.dumps(figures))
        return
    shown = [k for k in figures if k not in leave_out]
    width = max((len(k) for k in shown), default=0)
    for key in shown:
        print(f"{key:>{width}}: {figures[key]}")
