"""A ship model learned from the ship's own records (ROS-free): physics prior + neural residual.

`features` turns cleaned segment means into network inputs and the ship file's physics prior,
`train` fits the ensembles (scikit-learn), `model` holds and predicts them (numpy only) and
reads/writes the NetCDF model file, `tables` calibrates the planner's fast tables to the
learned ship and `select` resolves the planner's `--model` choice.
"""

from .errors import LearnError, ModelFileError, TrainingDataError, WrongShipError

__all__ = ["LearnError", "ModelFileError", "TrainingDataError", "WrongShipError"]
