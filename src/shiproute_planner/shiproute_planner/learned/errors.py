"""Errors of the learned ship model (one base class, specific subclasses)."""

from __future__ import annotations

from ..ship.errors import ShipModelError


class LearnError(ShipModelError):
    """Base class of every error raised while learning or using a learned ship model."""


class TrainingDataError(LearnError):
    """Records cannot train a model (missing columns, units, too few clean segments)."""


class ModelFileError(LearnError):
    """A learned-model file is missing, unreadable or not a shiproute learned model."""


class WrongShipError(LearnError):
    """A learned model was trained for another ship than the one it is used with."""
