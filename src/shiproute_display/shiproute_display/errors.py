"""Errors raised by the display library: one base class, specific subclasses naming the input."""

from __future__ import annotations


class DisplayError(Exception):
    """Base class of every error the display library raises on purpose."""


class MalformedMessageError(DisplayError):
    """A received message cannot be shown (missing, non-finite or inconsistent values)."""


class DisplayConfigError(DisplayError):
    """A display parameter (port, bind address, limits) is invalid."""
