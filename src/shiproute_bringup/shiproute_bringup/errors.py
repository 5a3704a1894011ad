"""Errors of shiproute_bringup: one base class, specific subclasses naming the bad input."""

from __future__ import annotations


class BringupError(Exception):
    """Base error of the shiproute_bringup package."""


class BringupFileError(BringupError):
    """A bringup YAML file is missing, unreadable or malformed (message names file and entry)."""


class ProcessTimeoutError(BringupError, TimeoutError):
    """A wait on a child process (output line, condition, exit) ran past its deadline."""


class EchoError(BringupError):
    """`shiproute echo` cannot resolve a topic or message type."""
