"""Echo process for the interface round-trip test: republish, answer services, run an action.

Run: ``python roundtrip_echo.py Type1 Type2 ...`` with ROS_DOMAIN_ID set. For each message type
``shiproute_msgs/msg/<T>`` it subscribes to ``/rt/in/<T>`` and republishes the received object
unchanged on ``/rt/out/<T>`` (both transient local, reliable). Services under ``/rt/srv/<Srv>``
answer with values derived from the request (see the handlers); the ``/rt/plan`` action sends
two feedbacks and a result. Prints ``READY`` when everything exists.
"""

from __future__ import annotations

import json
import math
import sys

import rclpy
from rclpy.action import ActionServer
from rclpy.executors import ExternalShutdownException, SingleThreadedExecutor
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy

import shiproute_msgs.msg as msgs
from shiproute_msgs.action import PlanRoute
from shiproute_msgs.srv import LoadForecast, Seek, SetVoyage

QOS = QoSProfile(depth=10, durability=DurabilityPolicy.TRANSIENT_LOCAL,
                 reliability=ReliabilityPolicy.RELIABLE)


def load_forecast(req: LoadForecast.Request, res: LoadForecast.Response) -> LoadForecast.Response:
    """accepted iff paths given; cycle_id = paths joined by '|'; message = number of paths."""
    res.accepted = len(req.paths) > 0
    res.cycle_id = "|".join(req.paths)
    res.message = str(len(req.paths))
    return res


def seek(req: Seek.Request, res: Seek.Response) -> Seek.Response:
    """success iff offset is finite and >= 0; message = repr of the offset received."""
    res.success = math.isfinite(req.offset_s) and req.offset_s >= 0.0
    res.message = repr(req.offset_s)
    return res


def set_voyage(req: SetVoyage.Request, res: SetVoyage.Response) -> SetVoyage.Response:
    """accepted; message = JSON of every request field as received."""
    res.accepted = True
    res.message = json.dumps({
        "destination": req.destination, "destination_lat_deg": req.destination_lat_deg,
        "destination_lon_deg": req.destination_lon_deg,
        "rta": [req.rta.sec, req.rta.nanosec], "ship": req.ship, "objective": req.objective})
    return res


def plan(goal_handle: object) -> PlanRoute.Result:
    """Two feedbacks (generation 1, 2), then success with plan_id = the goal's reason."""
    request = goal_handle.request  # type: ignore[attr-defined]
    for generation in (1, 2):
        feedback = PlanRoute.Feedback(generation=generation, evaluations=100 * generation,
                                      best_fuel_t=math.nan if generation == 1 else 12.5,
                                      elapsed_s=0.1 * generation)
        goal_handle.publish_feedback(feedback)  # type: ignore[attr-defined]
    goal_handle.succeed()  # type: ignore[attr-defined]
    return PlanRoute.Result(success=True, plan_id=request.reason,
                            message=f"budget {request.budget_s!r}")


def main(type_names: list[str]) -> int:
    """Create the republishers, services and action server, then spin until shut down."""
    rclpy.init()
    node = Node("roundtrip_echo")
    keep = []
    for name in type_names:
        cls = getattr(msgs, name)
        pub = node.create_publisher(cls, f"/rt/out/{name}", QOS)
        keep.append(pub)
        keep.append(node.create_subscription(cls, f"/rt/in/{name}",
                                             lambda m, p=pub: p.publish(m), QOS))
    keep.append(node.create_service(LoadForecast, "/rt/srv/LoadForecast", load_forecast))
    keep.append(node.create_service(Seek, "/rt/srv/Seek", seek))
    keep.append(node.create_service(SetVoyage, "/rt/srv/SetVoyage", set_voyage))
    keep.append(ActionServer(node, PlanRoute, "/rt/plan", plan))
    print("READY", flush=True)
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    try:
        executor.spin()
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
