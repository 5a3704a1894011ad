"""Fleet planning: many voyages x forecasts planned on a Dask cluster with the same planner as
`shiproute plan` (request builder `plan_request`), outputs written once per voyage, a fleet
summary (CSV + plot), re-runs skipping what is already planned for the same inputs."""
