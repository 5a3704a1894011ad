"""Forecast files (GRIB1/2, NetCDF, projected grids, several sources) -> one validated
canonical dataset, and from it the bounded cycle of slices the node publishes."""
