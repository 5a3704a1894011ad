"""What the display knows, behind one lock: plans, schedule, ship, forecast views, counters.

Each `on_*` method takes a checked library value, updates the state and returns the events
(name, JSON-ready payload) to push to the pages; `snapshot()` is what a page gets on connect.
ROS-free: the node converts messages (counting the malformed ones through `malformed`).
"""

from __future__ import annotations

import math
import threading
import time
from collections import OrderedDict, deque
from typing import Any

from . import geometry
from .coastline import ChartBox
from .ensemble_view import combined_view, hs_peak_track, member_slice_index, valid_times
from .forecast_view import SliceView
from .geojson import baseline_points, chart_geojson
from .model import CycleInfo, Plan, Profile, ShipFix
from .page_payload import fix_payload, history_row, plan_payload

Event = tuple[str, dict[str, Any]]
TRACK_MIN_STEP_DEG = 0.02  #: track points closer than this (~1 NM) to the last one are not kept


class DisplayState:
    """Thread-safe store of everything the page shows."""

    def __init__(self, track_max_points: int = 5000, history_max: int = 50,
                 max_cycles: int = 2) -> None:
        self._lock = threading.Lock()
        self.plan: Plan | None = None
        self.previous: Plan | None = None
        self.voyage_start: Plan | None = None
        self.profiles: OrderedDict[str, Profile] = OrderedDict()
        self.history: deque[dict[str, Any]] = deque(maxlen=history_max)
        self.ship: ShipFix | None = None
        self.track: deque[tuple[float, float]] = deque(maxlen=track_max_points)
        self.cycles: OrderedDict[str, CycleInfo] = OrderedDict()
        self.slices: dict[str, dict[int, SliceView]] = {}
        self.tracks: dict[str, list[list[list[float]]]] = {}  # per complete cycle, per member
        self.combined: dict[tuple[str, int], SliceView] = {}  # (cycle, time index) P90 views
        self.max_cycles = max_cycles
        self.received: dict[str, int] = {}
        self.malformed_counts: dict[str, int] = {}
        self.last_problem = ""
        self.started_wall = time.time()

    # ------------------------------------------------------------------ inputs
    def count(self, topic: str) -> None:
        """One message received on `topic` (well-formed or not)."""
        with self._lock:
            self.received[topic] = self.received.get(topic, 0) + 1

    def malformed(self, topic: str, problem: str) -> Event:
        """A message on `topic` that could not be shown; returns the stats event."""
        with self._lock:
            self.malformed_counts[topic] = self.malformed_counts.get(topic, 0) + 1
            self.last_problem = f"{topic}: {problem}"
            return "stats", self._stats()

    def on_plan(self, plan: Plan) -> list[Event]:
        """A new plan becomes current, the current one previous; history grows by one row."""
        with self._lock:
            if self.plan is not None and self.plan.plan_id == plan.plan_id:
                return []  # the same plan again (late-joiner redelivery)
            if self.voyage_start is None or self._new_voyage(plan):
                self.voyage_start = plan
            self.previous, self.plan = self.plan, plan
            self.history.append(history_row(plan, self.previous))
            return [("plan", self._plan_event())]

    def on_profile(self, profile: Profile) -> list[Event]:
        """An RpmProfile; when it belongs to the current plan the schedule is re-sent."""
        with self._lock:
            self.profiles[profile.plan_id] = profile
            while len(self.profiles) > 4:
                self.profiles.popitem(last=False)
            if self.plan is not None and profile.plan_id == self.plan.plan_id:
                return [("plan", self._plan_event())]
            return []

    def on_fix(self, fix: ShipFix) -> None:
        """Latest own-ship fix; the track keeps points ~1 NM apart (pushed by `ship_event`)."""
        with self._lock:
            self.ship = fix
            p = (fix.lat_deg, fix.lon_deg)
            if not self.track or (abs(p[0] - self.track[-1][0]) + abs(
                    geometry.wrap_lon(p[1] - self.track[-1][1])) >= TRACK_MIN_STEP_DEG):
                self.track.append(p)

    def on_cycle(self, info: CycleInfo) -> list[Event]:
        """A forecast cycle announcement (the oldest cycle beyond `max_cycles` is forgotten)."""
        with self._lock:
            self.cycles[info.cycle_id] = info
            self.cycles.move_to_end(info.cycle_id)
            views = self.slices.setdefault(info.cycle_id, {})
            if len(views) == info.slice_count:  # every slice came before the announcement
                self.tracks[info.cycle_id] = self._member_tracks(info, views)
            while len(self.cycles) > self.max_cycles:
                old, _ = self.cycles.popitem(last=False)
                self.slices.pop(old, None)
                self._forget_views(old)
            return [("forecast", self._forecast_summary())]

    def on_slice(self, cycle_id: str, view: SliceView) -> list[Event]:
        """A thinned slice; an event only when its cycle becomes complete (no per-slice spam).

        Slices may arrive before their announcement (separate topics): they are kept for at
        most one cycle not yet announced."""
        with self._lock:
            if cycle_id not in self.slices:
                for old in [c for c in self.slices if c not in self.cycles]:
                    del self.slices[old]  # an earlier unannounced cycle: superseded
            views = self.slices.setdefault(cycle_id, {})
            views[view.index] = view
            info = self.cycles.get(cycle_id)
            if info is not None and len(views) == info.slice_count:
                self._forget_views(cycle_id)  # a re-published cycle: views anew
                self.tracks[cycle_id] = self._member_tracks(info, views)
                return [("forecast", self._forecast_summary())]
            return []

    def _forget_views(self, cycle_id: str) -> None:
        """Drop a cycle's derived views (locked)."""
        self.tracks.pop(cycle_id, None)
        for key in [k for k in self.combined if k[0] == cycle_id]:
            del self.combined[key]

    @staticmethod
    def _member_tracks(info: CycleInfo, views: dict[int, SliceView]) -> list[list[list[float]]]:
        """Each member's Hs-peak track of a complete ensemble cycle ([] for one member)."""
        if info.member_count < 2:
            return []
        per = info.times_per_member
        return [hs_peak_track([views[member_slice_index(m, k, per)] for k in range(per)])
                for m in range(info.member_count)]

    # ------------------------------------------------------------------ outputs
    def now_s(self) -> float:
        """Ship's time: the latest fix, else the wall clock."""
        with self._lock:
            return self.ship.time_s if self.ship is not None else time.time()

    def ship_event(self, track_since: int) -> tuple[Event | None, int]:
        """The latest fix and the track points after index `track_since` (None if no fix)."""
        with self._lock:
            if self.ship is None:
                return None, track_since
            pts = list(self.track)
            n = len(pts)
            new = pts[track_since:] if track_since <= n else pts
            payload = {"fix": fix_payload(self.ship), "track_add": [list(p) for p in new],
                       "stats": self._stats()}
            return ("ship", payload), n

    def snapshot(self) -> dict[str, Any]:
        """Everything a page needs on connect."""
        with self._lock:
            return {**self._plan_event(), "ship": fix_payload(self.ship) if self.ship else None,
                    "track": [list(p) for p in self.track],
                    "forecast": self._forecast_summary(), "stats": self._stats()}

    def slice_json(self, cycle_id: str, index: int, member: str = "0") -> bytes | None:
        """The thinned slice of a cycle at valid-time `index` of `member` (a number, or "p90":
        each cell's P90 over the members) as JSON, None when not held."""
        with self._lock:
            views = self.slices.get(cycle_id, {})
            info = self.cycles.get(cycle_id)
            members = info.member_count if info is not None else 1
            per = info.times_per_member if info is not None else max(1, len(views))
            if not 0 <= index < per:
                return None
            if member == "p90":
                key = (cycle_id, index)
                view = self.combined.get(key)
                if view is None:
                    held = [views.get(member_slice_index(m, index, per)) for m in range(members)]
                    if any(v is None for v in held):
                        return None  # the P90 of a partial cycle would not be a P90
                    view = combined_view([v for v in held if v is not None], index)
                    self.combined[key] = view
            else:
                try:
                    m = int(member)
                except ValueError:
                    return None
                view = views.get(member_slice_index(m, index, per)) if 0 <= m < members \
                    else None
        return view.to_json() if view is not None else None

    def chart_box(self) -> ChartBox | None:
        """Extent of plan, great circle, previous plan and track (continuous longitudes)."""
        with self._lock:
            pts: list[tuple[float, float]] = []
            for p in (self.plan, self.previous):
                if p is not None:
                    pts += [(w.lat_deg, w.lon_deg) for w in p.waypoints]
            if self.voyage_start is not None:
                pts += baseline_points(self.voyage_start, 32)
            pts += list(self.track)
        if not pts:
            return None
        lons = geometry.unwrap([p[1] for p in pts], pts[0][1])
        lats = [p[0] for p in pts]
        return ChartBox(min(lons), max(lons), min(lats), max(lats))

    def geojson(self) -> dict[str, Any]:
        """The chart as a GeoJSON FeatureCollection (Foxglove)."""
        with self._lock:
            return chart_geojson(self.plan, self.previous, self.voyage_start, list(self.track),
                                 self.ship)

    def current_plan(self) -> tuple[Plan | None, Profile | None]:
        """The current plan and its profile (if arrived)."""
        with self._lock:
            if self.plan is None:
                return None, None
            return self.plan, self.profiles.get(self.plan.plan_id)

    def stats(self) -> dict[str, Any]:
        """Counters for the page's status line."""
        with self._lock:
            return self._stats()

    # ------------------------------------------------------------------ helpers (locked)
    def _new_voyage(self, plan: Plan) -> bool:
        if self.voyage_start is None:
            return True
        a, b = self.voyage_start.waypoints[-1], plan.waypoints[-1]
        return abs(a.lat_deg - b.lat_deg) + abs(geometry.wrap_lon(a.lon_deg - b.lon_deg)) > 0.5

    def _plan_event(self) -> dict[str, Any]:
        plan, prev, start = self.plan, self.previous, self.voyage_start
        gc = baseline_points(start) if start is not None else []
        return {
            "plan": plan_payload(plan, self.profiles.get(plan.plan_id)) if plan else None,
            "previous": {"plan_id": prev.plan_id, "lat": [w.lat_deg for w in prev.waypoints],
                         "lon": [w.lon_deg for w in prev.waypoints]} if prev else None,
            "great_circle": {"lat": [round(p[0], 4) for p in gc],
                             "lon": [round(p[1], 4) for p in gc]},
            "history": list(self.history),
        }

    def _forecast_summary(self) -> dict[str, Any]:
        cycles = []
        for cid, info in self.cycles.items():
            views = self.slices.get(cid, {})
            indices, times = valid_times(views, info.member_count, info.slice_count)
            cycles.append({
                "cycle_id": cid, "reference_s": info.reference_s, "source": info.source,
                "slice_count": info.slice_count, "received": len(views),
                "members": info.member_count, "member_labels": list(info.member_labels),
                "member_kind": info.member_kind, "times_per_member": info.times_per_member,
                "times_s": times, "indices": indices,
                "tracks": self.tracks.get(cid, []),
            })
        return {"cycles": cycles}

    def _stats(self) -> dict[str, Any]:
        return {"received": dict(self.received), "malformed": dict(self.malformed_counts),
                "malformed_total": sum(self.malformed_counts.values()),
                "last_problem": self.last_problem,
                "uptime_s": round(time.time() - self.started_wall, 1),
                "now_s": self.ship.time_s if self.ship is not None else time.time()}


def finite_or(v: float, default: float) -> float:
    """`v` when finite, else `default`."""
    return v if math.isfinite(v) else default
