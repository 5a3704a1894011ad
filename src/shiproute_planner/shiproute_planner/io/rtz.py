"""RTZ 1.2 (IEC 61174) route file of a plan, with a calculated schedule, and validation.

`routeName` equals the file stem; waypoint ids are 1..N; each leg starts at the waypoint
before it, so waypoint k > 1 carries the leg from k - 1 (RTZ convention) and schedule element
k the ETA at k and the speed/RPM/fuel of the leg leaving k. RTZ requires integer RPM.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from datetime import UTC, datetime
from importlib import resources
from pathlib import Path

from shiproute_core.units import M_S_PER_KNOT

from ..errors import OutputError
from ..plan_types import RoutePlan

NS = "http://www.cirm.org/RTZ/1/2"
SCHEMA_FILE = "RTZ_Schema_version_1_2.xsd"


def _time(t_s: float) -> str:
    return datetime.fromtimestamp(t_s, UTC).strftime("%Y-%m-%dT%H:%M:%SZ")


def _num(x: float, nd: int = 3) -> str:
    return f"{x:.{nd}f}"


def rtz_tree(plan: RoutePlan, route_name: str) -> ET.ElementTree:
    """The RTZ document of `plan` as an ElementTree."""
    ET.register_namespace("", NS)
    q = lambda tag: f"{{{NS}}}{tag}"  # noqa: E731 - tiny local helper
    root = ET.Element(q("route"), {"version": "1.2"})
    info = {
        "routeName": route_name, "routeAuthor": "shiproute", "routeStatus": "planned",
        "validityPeriodStart": _time(plan.departure_s), "validityPeriodStop": _time(plan.eta_s),
        "vesselName": plan.ship_name or "unknown",
        "optimizationMethod": f"{plan.method} ({plan.objective}; seed {plan.seed_source})",
    }
    if plan.vessel_max_wave_m == plan.vessel_max_wave_m:
        info["vesselMaxWave"] = _num(plan.vessel_max_wave_m, 1)
    if plan.vessel_max_wind_m_s == plan.vessel_max_wind_m_s:
        info["vesselMaxWind"] = _num(plan.vessel_max_wind_m_s / M_S_PER_KNOT, 1)
    ET.SubElement(root, q("routeInfo"), info)
    wps = ET.SubElement(root, q("waypoints"))
    for k, w in enumerate(plan.waypoints):
        attrs = {"id": str(k + 1), "revision": "0"}
        if w.port:
            attrs["name"] = w.port
        el = ET.SubElement(wps, q("waypoint"), attrs)
        ET.SubElement(el, q("position"), {"lat": _num(w.lat_deg, 6), "lon": _num(w.lon_deg, 6)})
        if k > 0:
            prev = plan.waypoints[k - 1]
            ET.SubElement(el, q("leg"), {
                "geometryType": "Orthodrome",
                "speedMax": _num(max(prev.sog_kn, 0.0), 2),
                "legInfo": f"rpm {prev.shaft_rpm:.1f}, heading {prev.heading_deg:.1f} deg",
            })
    scheds = ET.SubElement(root, q("schedules"))
    sched = ET.SubElement(scheds, q("schedule"), {"id": "1", "name": "optimised"})
    calc = ET.SubElement(sched, q("calculated"))
    n = len(plan.waypoints)
    for k, w in enumerate(plan.waypoints):
        attrs = {"waypointId": str(k + 1)}
        if k > 0:
            attrs["eta"] = _time(w.time_s)
        if k < n - 1:
            attrs["etd"] = _time(w.time_s)
            attrs["speed"] = _num(max(w.sog_kn, 0.0), 2)
            attrs["rpm"] = str(max(round(w.shaft_rpm), 0))
            attrs["fuel"] = _num(w.leg_fuel_t, 3)
            if w.wind_speed_m_s == w.wind_speed_m_s:
                attrs["windSpeed"] = _num(w.wind_speed_m_s / M_S_PER_KNOT, 1)
            if w.wind_from_deg == w.wind_from_deg:
                attrs["windDirection"] = _num(w.wind_from_deg % 360.0, 1)
        ET.SubElement(calc, q("scheduleElement"), attrs)
    return ET.ElementTree(root)


def write_rtz(plan: RoutePlan, path: str | Path) -> Path:
    """Write `plan` as RTZ 1.2 to `path` (routeName = file stem)."""
    path = Path(path)
    tree = rtz_tree(plan, path.stem)
    ET.indent(tree)
    try:
        tree.write(path, encoding="utf-8", xml_declaration=True)
    except OSError as exc:
        raise OutputError(f"cannot write RTZ file {path}: {exc}") from exc
    return path


def validate_rtz(path: str | Path) -> None:
    """Raise OutputError unless `path` is valid RTZ 1.2 with routeName = file stem."""
    import xmlschema

    schema_path = resources.files("shiproute_planner.io") / SCHEMA_FILE
    schema = xmlschema.XMLSchema(str(schema_path))
    path = Path(path)
    errors = [str(e.reason) for e in schema.iter_errors(str(path))]
    if errors:
        raise OutputError(f"{path} is not valid RTZ 1.2: {errors[0]}")
    info = ET.parse(path).getroot().find(f"{{{NS}}}routeInfo")
    if info is None:
        raise OutputError(f"{path} has no routeInfo element")
    name = info.get("routeName")
    if name != path.stem:
        raise OutputError(f"{path}: routeName {name!r} does not match the file name")
