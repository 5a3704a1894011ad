"""An independent RFC 7946 checker for the tests (structure, positions, antimeridian)."""

from __future__ import annotations

import math
from itertools import pairwise
from typing import Any


def _position(p: Any) -> None:
    assert isinstance(p, list) and len(p) in (2, 3), f"position {p!r}"
    lon, lat = p[0], p[1]
    assert all(isinstance(v, int | float) and math.isfinite(v) for v in p), f"position {p!r}"
    assert -180.0 <= lon <= 180.0 and -90.0 <= lat <= 90.0, f"position {p!r} out of range"


def _line(coords: Any) -> None:
    assert isinstance(coords, list) and len(coords) >= 2, "a LineString needs >= 2 positions"
    for p in coords:
        _position(p)
    for a, b in pairwise(coords):
        assert abs(b[0] - a[0]) <= 180.0, f"segment {a} -> {b} jumps across the antimeridian"


def check_geometry(g: dict) -> None:
    """Assert a GeoJSON geometry is valid."""
    kind, coords = g["type"], g.get("coordinates")
    if kind == "Point":
        _position(coords)
    elif kind == "MultiPoint":
        for p in coords:
            _position(p)
    elif kind == "LineString":
        _line(coords)
    elif kind == "MultiLineString":
        assert coords, "empty MultiLineString"
        for c in coords:
            _line(c)
    elif kind == "Polygon":
        for ring in coords:
            assert len(ring) >= 4 and ring[0] == ring[-1], "polygon ring not closed"
            for p in ring:
                _position(p)
    else:
        raise AssertionError(f"unexpected geometry type {kind!r}")


def check_geojson(obj: dict) -> list[str]:
    """Assert `obj` is a valid FeatureCollection; returns the features' `name` properties."""
    assert obj.get("type") == "FeatureCollection", "not a FeatureCollection"
    names = []
    assert isinstance(obj["features"], list)
    for f in obj["features"]:
        assert f.get("type") == "Feature"
        assert isinstance(f.get("properties"), dict | None)
        check_geometry(f["geometry"])
        names.append((f.get("properties") or {}).get("name", ""))
    return names
