"""The planner node's forecast intake: announcements and slices into cycles, refusals counted.

Runs on the intake node's single thread (the only one that touches the assembler; the packing
kernel runs without the GIL). Every slice is checked before anything is allocated for it; the
slices of a refused cycle are counted and dropped; a complete cycle that is not older than the
one in force is handed to the planner through `take`.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

from shiproute_msgs.msg import ForecastCycle, ForecastSlice

from ..checks.forecast_wire import check_not_older, check_slice_count, check_slice_fields
from ..errors import PlannerError
from .convert import cycle_record, slice_fields
from .cycle_assembler import CycleAssembler
from .cycle_packer import CyclePacker, SliceFields
from .drop_log import DropLog
from .intake_keys import MembersSeen, RejectedKeys, assembly_key
from .member_packer import MemberCyclePacker

ANNOUNCEMENT = -1  # the slice index `feed` takes for a cycle announcement
CYCLE_RECORDS_KEPT = 8  # cycle records (what a cycle holds, where from) kept for the plans


class ForecastIntake:
    """Cycle assembly for the planner node; `in_force` gives the (cycle id, reference time) of
    the cycle in force, `take(sampler, cycle_id, reference_s)` puts a complete cycle in force,
    `report(text)` records and logs a refusal as the node's last error."""

    def __init__(self, drops: DropLog, logger: Any, *, accept_older: Callable[[], bool],
                 ship_time_s: Callable[[], float], in_force: Callable[[], tuple[str, float]],
                 take: Callable[[Any, str, float], None],
                 report: Callable[[str], None]) -> None:
        self._drops = drops
        self._logger = logger
        self._accept_older = accept_older
        self._ship_time_s = ship_time_s
        self._in_force = in_force
        self._take_cycle = take
        self._report = report
        # at most two cycles in flight (a superseded one's tail and its successor): each holds
        # a sampler array being filled beside the one in force
        self._assembler: CycleAssembler[SliceFields] = CycleAssembler(
            max_pending_cycles=2, sink=self._new_packer, on_evict=self._on_evict)
        self._rejected = RejectedKeys()
        self._cycle_records: dict[str, Any] = {}
        self._cycle_timing: dict[str, list[float]] = {}  # first slice arrival, packing [s]
        self._members_seen = MembersSeen()  # slices per member of cycles being assembled
        self.last_refusal = ""

    def on_cycle(self, msg: ForecastCycle) -> None:
        key = assembly_key(msg.cycle_id, msg.publication_id)
        try:
            check_slice_count(msg.cycle_id, int(msg.slice_count))
        except PlannerError as err:
            self._reject_cycle(key, msg.cycle_id, err)
            return
        # what the cycle holds and where from: stated by every plan made on it
        records = self._cycle_records
        records[msg.cycle_id] = cycle_record(msg)
        self._cycle_records = dict(list(records.items())[-CYCLE_RECORDS_KEPT:])
        self._feed(key, msg.cycle_id, ANNOUNCEMENT, int(msg.slice_count), None)

    def on_slice(self, msg: ForecastSlice) -> None:
        # a zero-copy view: packed straight from the message's buffers
        key = assembly_key(msg.cycle_id, msg.publication_id)
        self._cycle_timing.setdefault(key, [time.monotonic(), 0.0])
        item = slice_fields(msg)
        self._members_seen.note(key, item)
        self._feed(key, msg.cycle_id, int(msg.slice_index), int(msg.slice_count), item)

    def _feed(self, key: str, cycle_id: str, index: int, count: int,
              item: SliceFields | None) -> None:
        """An announcement or a slice into the assembler, and the cycle it completes, if any,
        into planning. Packing here, not on a thread of its own, spares a GIL hand-over per
        slice."""
        if key in self._rejected:
            if item is not None:
                self._drops.drop("forecast_slices", f"cycle {cycle_id!r} was refused: "
                                 f"{self._rejected.reason(key)}")
            return
        t0 = time.monotonic()
        try:
            if index == ANNOUNCEMENT:
                sampler = self._assembler.announce(key, count)
            else:
                assert item is not None
                check_slice_fields(item)
                sampler = self._assembler.add_slice(key, index, count, item)
        except Exception as err:  # a bad slice or cycle must not stop the intake
            self._reject_cycle(key, cycle_id, err, slices=0 if item is None else 1)
            return
        finally:
            timing = self._cycle_timing.get(key)
            if timing is not None:
                timing[1] += time.monotonic() - t0
        self._take(sampler, key, cycle_id)

    def _new_packer(self, _key: str, first: SliceFields) -> CyclePacker | MemberCyclePacker:
        """The sampler array (or, for several members, the member arrays) of a new cycle, made
        from its first (checked) slice once it is known not to be older than the one in
        force."""
        self._check_fresh(first.cycle_id, first.reference_time_s)
        if first.member_count > 1:
            return MemberCyclePacker(first)
        return CyclePacker(first, self._ship_time_s)

    def _check_fresh(self, cycle_id: str, reference_s: float) -> None:
        if not self._accept_older():
            in_force_id, in_force_reference_s = self._in_force()
            check_not_older(cycle_id, reference_s, in_force_id, in_force_reference_s)

    def _on_evict(self, key: str, received: int) -> None:
        """An incomplete cycle pushed out by newer ones: its slices are dropped, counted."""
        self._cycle_timing.pop(key, None)
        reason = (f"cycle {key!r} incomplete ({received} slice(s)"
                  f"{self._members_seen.missing_text(key)}) when newer cycles arrived")
        self._members_seen.forget(key)
        self._drops.drop("forecast_cycles", reason)
        if received:
            self._drops.drop("forecast_slices", reason, received)
        self.last_refusal = reason

    def _reject_cycle(self, key: str, cycle_id: str, err: Exception, slices: int = 0) -> None:
        """A bad slice or cycle is reported and counted; the cycle in force stays."""
        self._cycle_timing.pop(key, None)
        self._members_seen.forget(key)
        self._rejected.add(key, str(err))
        self._assembler.discard(key)  # not also counted as incomplete later
        kept = self._in_force()[0] or "none"
        text = f"forecast cycle {cycle_id!r} refused ({kept} stays in force): {err}"
        self.last_refusal = text
        self._drops.drop("forecast_cycles", str(err))
        if slices:
            self._drops.drop("forecast_slices", str(err), slices)
        self._report(text)

    def _take(self, sampler: Any, key: str, cycle_id: str) -> None:
        """A complete cycle's sampler replaces the current one and triggers a re-plan (unless
        a newer model run came into force while it streamed in)."""
        if sampler is None:
            return
        sampler.record = self._cycle_records.get(cycle_id)
        members = int(getattr(sampler, "member_count", 1))
        if members > 1:
            sampler.set_kind(str((sampler.record or {}).get("member_kind", "")))
        self._members_seen.forget(key)
        reference_s = float(getattr(sampler, "reference_time_s", 0.0))
        try:
            self._check_fresh(cycle_id, reference_s)
        except PlannerError as err:
            self._reject_cycle(key, cycle_id, err)
            return
        self._take_cycle(sampler, cycle_id, reference_s)
        first_s, pack_s = self._cycle_timing.pop(key, (time.monotonic(), 0.0))
        self._logger.info(
            f"forecast cycle {cycle_id} complete: {members} member(s), "
            f"{sampler.times_s.size} slices kept{' per member' if members > 1 else ''} "
            f"({sampler.nbytes / 2**20:.0f} MiB), received over {time.monotonic() - first_s:.2f} s"
            f" ({pack_s:.2f} s unpacking)")
