"""Benchmark scripts registered in the ``shiproute.bench`` entry-point group."""
