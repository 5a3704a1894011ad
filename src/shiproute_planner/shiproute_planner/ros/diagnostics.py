"""The planner node's /diagnostics status: intake, planning and the plan in force."""

from __future__ import annotations

import math
from typing import Any

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue

from ..plan_types import RoutePlan


def planner_status(values: dict[str, str], plan: RoutePlan | None, plan_age_s: float,
                   stamp: Any) -> DiagnosticArray:
    """One DiagnosticArray of the node's counters (`values`) and the plan in force: WARN while
    there is no plan or the plan is infeasible (the reasons are the message), OK otherwise."""
    status = DiagnosticStatus(name="shiproute_planner", hardware_id="shiproute")
    values = dict(values)
    if plan is None:
        status.level = DiagnosticStatus.WARN
        status.message = "no plan yet"
    else:
        status.level = DiagnosticStatus.OK if plan.feasible else DiagnosticStatus.WARN
        status.message = "plan feasible" if plan.feasible else "; ".join(
            plan.infeasible_reasons)
        values.update({
            "plan_id": plan.plan_id,
            "plan_cycle": plan.cycle_id,
            "plan_age_s": f"{plan_age_s:.1f}",
            "compute_time_s": f"{plan.compute_time_s:.3f}",
            "feasible": str(plan.feasible),
            "constraints": ", ".join(plan.infeasible_reasons) or "all met",
            "warnings": "; ".join(plan.warnings) or "none",
            "fuel_t": f"{plan.total_fuel_t:.2f}",
            "eta_minus_rta_h": f"{(plan.eta_s - plan.rta_s) / 3600:.2f}",
            **replan_values(plan),
        })
    status.values = [KeyValue(key=k, value=v) for k, v in values.items()]
    msg = DiagnosticArray(status=[status])
    msg.header.stamp = stamp
    return msg


def replan_values(plan: RoutePlan) -> dict[str, str]:
    """A re-plan's word on the previous plan (`replan_keep`): whether it was kept, what its
    remainder came to on the new forecast, and the sentence why it was kept."""
    block = plan.extra.get("replan")
    if not isinstance(block, dict):
        return {}
    if not block.get("carried"):
        return {"replan_previous_plan": f"not carried over: {block.get('why_not', '')}"}
    kept = next((w for w in plan.warnings if w.startswith("kept previous plan")), "")
    return {
        "replan_kept_previous": str(bool(block.get("kept_previous"))),
        "replan_previous_remaining_fuel_t": f"{block['previous_remaining_fuel_t']:.2f}",
        "replan_previous_remaining_feasible": str(block["previous_remaining_feasible"]),
        "replan_search_generations": str(block["generations"]),
        **({"replan_kept_why": kept} if kept else {}),
    }


def plan_log_line(plan: RoutePlan, reason: str) -> str:
    """The one log line of a published plan: fuel, ETA against RTA, saving and run time."""
    return (
        f"plan {plan.plan_id} cycle {plan.cycle_id}: fuel {plan.total_fuel_t:.1f} t, "
        f"ETA-RTA {(plan.eta_s - plan.rta_s) / 3600:+.1f} h, saved {plan.fuel_saving_t:.1f} t "
        f"vs constant RPM{'' if plan.baseline_feasible else ' (infeasible)'}, "
        f"{plan.compute_time_s:.2f} s, {plan.generations} gens, "
        f"feasible={plan.feasible}"
        + (" (kept previous plan)" if plan.extra.get("replan", {}).get("kept_previous")
           else "") + f" ({reason})"
    )


def progress_values(progress: Any) -> dict[str, float]:
    """Generation, evaluations and best objective of a planner progress report."""
    return {
        "generation": float(getattr(progress, "generation", 0)),
        "evaluations": float(getattr(progress, "evaluations", 0)),
        "best_objective": float(getattr(progress, "best_objective", math.nan)),
    }
