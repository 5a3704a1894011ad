"""Wave physics shared by ingest (waves estimated from wind) and the scenarios: spectral
periods, fetch/duration-limited growth, fetch over the land/sea mask."""
