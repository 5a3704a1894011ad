"""rosbags typestore for ROS 2 Kilted plus the shiproute_msgs interfaces, built from .msg text.

The message definitions are found in the installed share directory of the venv
(``$VENV/share/shiproute_msgs/msg``) and otherwise in the source tree, so no rclpy is needed.
"""

from __future__ import annotations

import sys
from functools import lru_cache
from pathlib import Path

from rosbags.typesys import Stores, get_types_from_msg, get_typestore
from rosbags.typesys.store import Typestore

from ..errors import MessageTypeError

SHIP_STATE_TYPE = "shiproute_msgs/msg/ShipState"
NAV_SAT_FIX_TYPE = "sensor_msgs/msg/NavSatFix"
CLOCK_TYPE = "rosgraph_msgs/msg/Clock"
TWIST_TYPES = ("geometry_msgs/msg/TwistStamped", "geometry_msgs/msg/TwistWithCovarianceStamped")


def shiproute_msg_dirs() -> list[Path]:
    """Candidate directories holding shiproute_msgs/msg/*.msg, installed share dir first."""
    repo_dir = Path(__file__).resolve().parents[2] / "shiproute_msgs" / "msg"
    return [Path(sys.prefix) / "share" / "shiproute_msgs" / "msg", repo_dir]


def find_msg_dir() -> Path:
    """First directory that holds ShipState.msg; raises when neither location has it."""
    for cand in shiproute_msg_dirs():
        if (cand / "ShipState.msg").is_file():
            return cand
    raise MessageTypeError(
        f"shiproute_msgs .msg files not found in any of {[str(p) for p in shiproute_msg_dirs()]}"
    )


@lru_cache(maxsize=1)
def build_typestore() -> Typestore:
    """Kilted typestore with every shiproute_msgs message registered (cached per process)."""
    store = get_typestore(Stores.ROS2_KILTED)
    msg_dir = find_msg_dir()
    types: dict = {}
    for path in sorted(msg_dir.glob("*.msg")):
        name = f"shiproute_msgs/msg/{path.stem}"
        try:
            types.update(get_types_from_msg(path.read_text(encoding="utf-8"), name))
        except Exception as exc:  # rosbags raises several parser error types
            raise MessageTypeError(f"cannot parse message definition {path}: {exc}") from exc
    store.register(types)
    return store


def register_schema(store: Typestore, typename: str, text: str) -> bool:
    """Register a bag's embedded ros2msg schema; False when the text cannot be parsed.

    Types the store already knows are kept as they are (the bag's copy must agree with them
    for CDR to decode at all, and re-registering a differing copy raises in rosbags).
    """
    if typename in store.fielddefs:
        return True
    if not text.strip():
        return False
    try:
        types = get_types_from_msg(text, typename)
        store.register({k: v for k, v in types.items() if k not in store.fielddefs})
    except Exception:  # unparseable or conflicting definitions: the type stays unknown
        return False
    return typename in store.fielddefs


def msgdef(store: Typestore, typename: str) -> str:
    """Concatenated ros2msg definition text of ``typename`` as rosbag2 embeds it."""
    if typename not in store.fielddefs:
        raise MessageTypeError(f"message type {typename!r} is not known to the typestore")
    return store.generate_msgdef(typename, ros_version=2)[0]
