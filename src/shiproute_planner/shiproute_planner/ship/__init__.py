"""Ship performance-evaluation model (ROS-free): ship files, physics chain, fast tables."""

from .errors import InputRangeError, ProfileError, ShipFileError, ShipModelError, UnknownShipError
from .fast import FastModel, fast_model
from .loading import bundled_ships, load_ship, parse_ship
from .performance import LegPerformance, PerformanceModel
from .physics import PhysicsModel
from .seastate import SeaState
from .spec import ShipSpec

__all__ = [
    "FastModel",
    "InputRangeError",
    "LegPerformance",
    "PerformanceModel",
    "PhysicsModel",
    "ProfileError",
    "SeaState",
    "ShipFileError",
    "ShipModelError",
    "ShipSpec",
    "UnknownShipError",
    "bundled_ships",
    "fast_model",
    "load_ship",
    "parse_ship",
]
