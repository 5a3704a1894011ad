"""The canonical forecast contract: CF variable names, SI units, UTC times, grid checks.

Every other room speaks this dataset; this room imports nothing of the package but `errors`."""
