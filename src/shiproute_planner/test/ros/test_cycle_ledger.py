"""Every accepted forecast cycle is accounted for: planned, failed or superseded (named)."""

from __future__ import annotations

from shiproute_planner.ros.cycle_ledger import CycleLedger


def test_cycle_planned_before_the_next_is_not_superseded() -> None:
    ledger = CycleLedger()
    for cid in ("a", "b", "a", "b"):
        ledger.taken(cid)
        ledger.answered(cid, planned=True)
    v = ledger.values()
    assert (v["forecast_cycles_planned"], v["forecast_cycles_superseded"]) == ("4", "0")
    assert v["forecast_cycles_superseded_last"] == "none"


def test_cycles_coalesced_while_planning_are_counted_and_named() -> None:
    ledger = CycleLedger()
    ledger.taken("a")
    ledger.taken("b")  # arrived before a plan on a
    ledger.taken("c")  # and c before a plan on b
    ledger.answered("c", planned=True)
    v = ledger.values()
    assert v["forecast_cycles_superseded"] == "2"
    assert v["forecast_cycles_superseded_last"] == "b (superseded by c)"
    assert (v["forecast_cycles_accepted"], v["forecast_cycles_planned"]) == ("3", "1")
    assert v["forecast_cycle_in_force_answered"] == "True"


def test_a_plan_on_an_older_cycle_does_not_answer_the_one_in_force() -> None:
    ledger = CycleLedger()
    ledger.taken("a")
    ledger.taken("b")
    ledger.taken("c")
    ledger.answered("a", planned=True)  # neither in force nor just superseded
    v = ledger.values()
    assert (v["forecast_cycles_planned"], v["forecast_cycles_superseded"]) == ("0", "2")
    assert v["forecast_cycle_in_force_answered"] == "False"


def test_plan_published_as_the_next_cycle_arrived_counts_as_planned() -> None:
    ledger = CycleLedger()
    ledger.taken("a")
    ledger.taken("b")  # the run on a had passed its cancel check
    ledger.answered("a", planned=True)
    ledger.answered("b", planned=False)
    v = ledger.values()
    assert (v["forecast_cycles_planned"], v["forecast_cycles_failed"],
            v["forecast_cycles_superseded"]) == ("1", "1", "0")


def test_same_cycle_id_accepted_again_is_a_new_entry() -> None:
    ledger = CycleLedger()
    ledger.taken("a")
    ledger.answered("a", planned=True)
    ledger.taken("a")  # the same file reloaded
    assert ledger.values()["forecast_cycle_in_force_answered"] == "False"
    ledger.answered("a", planned=True)
    assert ledger.values()["forecast_cycles_planned"] == "2"
