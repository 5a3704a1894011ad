"""Errors of shiproute_ais_replay: one base class, specific subclasses naming input and fault."""

from __future__ import annotations


class AisReplayError(Exception):
    """Base of every error raised by the bag tools, AIS import, simulation and replay."""


class BagOpenError(AisReplayError):
    """A bag path does not exist or is not a rosbag2 MCAP directory / .mcap file."""


class BagFormatError(AisReplayError):
    """A bag's bytes are not MCAP at all (bad magic) so nothing can be recovered."""


class BagWriteError(AisReplayError):
    """A bag could not be written (target exists, unknown type, closed writer)."""


class MessageTypeError(AisReplayError):
    """A message type definition is missing or cannot be parsed."""


class AisInputError(AisReplayError):
    """An AIS input file (NMEA or CSV) cannot be read or has no usable columns."""


class SimulationError(AisReplayError):
    """A voyage cannot be simulated (bad plan, missing forecast, bad arguments)."""
