"""Voyage simulation: a ship model sailing a planned route (RTZ, plan JSON or great circle)."""
