"""Vectorised sampling of a canonical forecast at (lon, lat, time) points: the sampler, its
half-precision storage, the public numba kernels compiled route code may call, time coverage."""
