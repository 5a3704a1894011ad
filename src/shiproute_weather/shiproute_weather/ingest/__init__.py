"""Forecast files (GRIB1/2, NetCDF, projected grids, several sources) -> one validated
canonical dataset; the bounded cycle of slices the node publishes; a forecast's coverage of a
voyage in time (persistence, monthly climatology beyond it)."""
