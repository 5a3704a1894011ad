"""Benchmarks of the weather package (`shiproute bench weather`): not part of the product."""
