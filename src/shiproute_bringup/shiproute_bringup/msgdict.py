"""Convert generated ROS message objects to plain dicts/lists (duck-typed; no rclpy import)."""

from __future__ import annotations

import importlib
import math
from typing import Any

from shiproute_bringup.errors import EchoError


def message_class(type_name: str) -> type:
    """Class for ``pkg/msg/Type`` (also ``pkg/Type`` and ``pkg.msg.Type``)."""
    parts = type_name.replace(".", "/").split("/")
    if len(parts) == 2:
        parts = [parts[0], "msg", parts[1]]
    if len(parts) != 3 or not all(parts):
        raise EchoError(f"message type '{type_name}' is not of the form pkg/msg/Type")
    pkg, kind, name = parts
    try:
        module = importlib.import_module(f"{pkg}.{kind}")
        return getattr(module, name)
    except (ImportError, AttributeError) as exc:
        raise EchoError(f"message type '{type_name}' is not installed: {exc}") from exc


def to_plain(value: Any, max_array: int | None = None) -> Any:
    """Messages -> dicts (field order kept), sequences/arrays -> lists, floats kept (NaN too).

    Sequences longer than ``max_array`` are cut to their first ``max_array`` items followed by
    a string noting the full length (for display only).
    """
    if hasattr(value, "get_fields_and_field_types"):
        return {name: to_plain(getattr(value, name), max_array)
                for name in value.get_fields_and_field_types()}
    if isinstance(value, (bytes, bytearray)):
        return list(value)
    if isinstance(value, (str, bool, int, float)) or value is None:
        return value
    if hasattr(value, "tolist") and not hasattr(value, "__len__"):
        return value.tolist()  # numpy scalar
    try:
        items = list(value)
    except TypeError:
        return repr(value)
    if max_array is not None and len(items) > max_array:
        shown = [to_plain(v, max_array) for v in items[:max_array]]
        return [*shown, f"... ({len(items)} values)"]
    return [to_plain(v.item() if hasattr(v, "item") else v, max_array) for v in items]


def plain_equal(a: Any, b: Any, rel_tol: float = 0.0) -> bool:
    """Deep equality of plain values with NaN == NaN (for round-trip checks)."""
    if isinstance(a, float) and isinstance(b, float):
        if math.isnan(a) and math.isnan(b):
            return True
        return a == b if rel_tol == 0.0 else math.isclose(a, b, rel_tol=rel_tol)
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(plain_equal(a[k], b[k], rel_tol) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(plain_equal(x, y, rel_tol) for x, y in zip(a, b,
                                                                                    strict=True))
    return bool(a == b)
