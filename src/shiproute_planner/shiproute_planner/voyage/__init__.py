"""Voyages of every shape: port calls, leg schedules and stage lengths."""
