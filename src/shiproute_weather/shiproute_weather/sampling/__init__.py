"""Vectorised sampling of a canonical forecast at (lon, lat, time) points: the sampler, its
half-precision storage and the public numba kernels compiled route code may call."""
