"""Ship performance-evaluation model (ROS-free): ship files, physics chain, fast tables."""

from .errors import InputRangeError, ProfileError, ShipFileError, ShipModelError, UnknownShipError
from .fast import FastModel, fast_model
from .kwon import KwonModel
from .loading import bundled_ships, load_ship, parse_ship
from .performance import LegPerformance, PerformanceModel
from .physics import PhysicsModel
from .profile import ProfileGrid, ProfileModel, export_profile
from .seastate import SeaState
from .spec import ShipSpec

__all__ = [
    "FastModel",
    "InputRangeError",
    "KwonModel",
    "LegPerformance",
    "PerformanceModel",
    "PhysicsModel",
    "ProfileError",
    "ProfileGrid",
    "ProfileModel",
    "SeaState",
    "ShipFileError",
    "ShipModelError",
    "ShipSpec",
    "UnknownShipError",
    "bundled_ships",
    "export_profile",
    "fast_model",
    "load_ship",
    "parse_ship",
]
