"""The learned ship model: physics prior x exp(neural residual), its uncertainty and its file.

Each output (shaft RPM, fuel rate) is the ship file's physics value at the same speed,
weather and drafts (the file's hull floating at the recorded drafts) times exp(r), where r
is the mean of an ensemble of single-hidden-layer ReLU networks on z-scored inputs
(reference 003's network, several of them for predictive uncertainty: the ensemble spread is
reported as a relative standard deviation). Outside the training range
the residual fades linearly to zero over ``fallback_std`` standard deviations of the input
beyond the range, so the model falls back to the physics model there (and says so).

File format (NetCDF, CF-style attributes; `LearnedModel.save` / `load`): global attributes
``format`` = FORMAT, ``ship_name``, ``ship_identity`` (sha256 of hull, propeller, engine and
windage of the ship file; a model is refused for any other ship), ``features`` (JSON list),
``reference_draft_fore_m``/``_aft_m`` (drafts of the latest training voyage: the drafts the
planner uses), ``fallback_std``, ``report`` (JSON: cleaning counts, metrics, training ranges);
variables ``x_mean``, ``x_std``, ``x_lo``, ``x_hi`` (feature) and per output o in (rpm, fuel):
``o_w0`` (o_member, feature, o_hidden), ``o_b0`` (o_member, o_hidden), ``o_w1`` (o_member,
o_hidden), ``o_b1`` (o_member), scalars ``o_y_mean``, ``o_y_std`` (target z-score).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import numpy.typing as npt

from ..ship.seastate import SeaState
from ..ship.spec import ShipSpec
from .errors import ModelFileError, WrongShipError
from .features import FEATURES, feature_matrix, physics_prior, ship_identity

FORMAT = "shiproute-learned-ship-model-1"
OUTPUTS = ("rpm", "fuel")


@dataclass(frozen=True)
class Network:
    """An ensemble of single-hidden-layer ReLU networks on z-scored inputs and target."""

    w0: np.ndarray  # (member, feature, hidden)
    b0: np.ndarray  # (member, hidden)
    w1: np.ndarray  # (member, hidden)
    b1: np.ndarray  # (member,)
    y_mean: float
    y_std: float

    def members(self, xz: np.ndarray) -> np.ndarray:
        """Predictions (member, n) for z-scored inputs xz (n, feature)."""
        h = np.maximum(np.einsum("nf,kfh->knh", xz, self.w0) + self.b0[:, None, :], 0.0)
        return (np.einsum("knh,kh->kn", h, self.w1) + self.b1[:, None]) * self.y_std + self.y_mean


@dataclass(frozen=True)
class Prediction:
    """Learned and prior values per point; ``weight`` 1 inside the training range, 0 = physics."""

    rpm: np.ndarray
    fuel_t_per_h: np.ndarray
    rpm_rel_std: np.ndarray  # ensemble spread of the RPM residual (relative)
    fuel_rel_std: np.ndarray
    weight: np.ndarray
    physics_rpm: np.ndarray
    physics_fuel_t_per_h: np.ndarray


@dataclass(frozen=True)
class LearnedModel:
    """Learned residual model of one ship (see the module docstring)."""

    ship_name: str
    ship_identity: str
    x_mean: np.ndarray
    x_std: np.ndarray
    x_lo: np.ndarray
    x_hi: np.ndarray
    rpm: Network
    fuel: Network
    reference_draft_fore_m: float
    reference_draft_aft_m: float
    fallback_std: float = 1.0
    report: dict = field(default_factory=dict, compare=False)

    def check_ship(self, ship: ShipSpec, source: str = "learned model") -> None:
        """Raise `WrongShipError` unless ``ship`` is the ship this model was trained for."""
        if ship.name != self.ship_name or ship_identity(ship) != self.ship_identity:
            same = "a changed ship file of " if ship.name == self.ship_name else ""
            raise WrongShipError(
                f"{source} was trained for ship '{self.ship_name}', not for {same}'{ship.name}' "
                f"(hull/propeller/engine identity {self.ship_identity[:12]} vs "
                f"{ship_identity(ship)[:12]}); learn a model from this ship's own records")

    def weight(self, x: np.ndarray) -> np.ndarray:
        """1 inside the training range, fading to 0 over ``fallback_std`` std beyond it."""
        over = np.maximum((x - self.x_hi) / self.x_std, (self.x_lo - x) / self.x_std)
        d = np.max(np.maximum(over - 1e-9, 0.0), axis=1)  # rounding at the range's ends
        return np.clip(1.0 - d / self.fallback_std, 0.0, 1.0)

    def residuals(self, x: np.ndarray) -> dict[str, np.ndarray]:
        """Log residuals (mean, spread) of both outputs and the fallback weight at inputs x."""
        xz = (x - self.x_mean) / self.x_std
        w = self.weight(x)
        out = {"weight": w}
        for name in OUTPUTS:
            m = getattr(self, name).members(xz)
            out[name] = w * m.mean(axis=0)
            out[f"{name}_std"] = w * m.std(axis=0)
        return out

    def predict(self, ship: ShipSpec, stw_kn: np.ndarray, heading_deg: np.ndarray,
                draft_fore_m: npt.ArrayLike, draft_aft_m: npt.ArrayLike,
                sea: SeaState) -> Prediction:
        """RPM and fuel rate the ship needs for ``stw_kn`` (1-D arrays) in ``sea``."""
        x = feature_matrix(stw_kn, heading_deg, draft_fore_m, draft_aft_m, sea)
        n = x.shape[0]
        hdg = np.broadcast_to(np.asarray(heading_deg, dtype=float), (n,))
        rpm0, fuel0 = physics_prior(ship, x[:, 0], hdg, sea.broadcast((n,)),
                                    np.broadcast_to(draft_fore_m, (n,)),
                                    np.broadcast_to(draft_aft_m, (n,)))
        r = self.residuals(x)
        return Prediction(rpm0 * np.exp(r["rpm"]), fuel0 * np.exp(r["fuel"]),
                          r["rpm_std"], r["fuel_std"], r["weight"], rpm0, fuel0)

    # -- file ---------------------------------------------------------------------------
    def save(self, path: str | Path) -> None:
        """Write the NetCDF model file (written to a temporary name, then renamed)."""
        import xarray as xr

        data: dict = {
            "x_mean": ("feature", self.x_mean), "x_std": ("feature", self.x_std),
            "x_lo": ("feature", self.x_lo), "x_hi": ("feature", self.x_hi),
        }
        for o in OUTPUTS:
            net: Network = getattr(self, o)
            m, h = f"{o}_member", f"{o}_hidden"
            data.update({
                f"{o}_w0": ((m, "feature", h), net.w0), f"{o}_b0": ((m, h), net.b0),
                f"{o}_w1": ((m, h), net.w1), f"{o}_b1": ((m,), net.b1),
                f"{o}_y_mean": ((), net.y_mean), f"{o}_y_std": ((), net.y_std),
            })
        ds = xr.Dataset(data, coords={"feature": list(FEATURES)}, attrs={
            "title": f"learned ship model: {self.ship_name}", "format": FORMAT,
            "ship_name": self.ship_name, "ship_identity": self.ship_identity,
            "features": json.dumps(list(FEATURES)),
            "reference_draft_fore_m": self.reference_draft_fore_m,
            "reference_draft_aft_m": self.reference_draft_aft_m,
            "fallback_std": self.fallback_std, "report": json.dumps(self.report),
            "model": "physics prior x exp(mean of single-hidden-layer ReLU ensemble)",
        })
        path = Path(path)
        tmp = path.with_name(path.name + ".part")
        ds.to_netcdf(tmp)
        tmp.replace(path)

    @classmethod
    def load(cls, path: str | Path) -> LearnedModel:
        """Read a model file written by `save` (raises `ModelFileError` naming the problem)."""
        import xarray as xr

        try:
            ds = xr.load_dataset(path)
        except (OSError, ValueError) as exc:
            raise ModelFileError(f"{path}: cannot read learned model: {exc}") from exc
        if ds.attrs.get("format") != FORMAT:
            raise ModelFileError(f"{path}: not a shiproute learned model (format attribute "
                                 f"{ds.attrs.get('format')!r}, expected {FORMAT!r})")
        if json.loads(ds.attrs["features"]) != list(FEATURES):
            raise ModelFileError(f"{path}: features {ds.attrs['features']} differ from "
                                 f"{list(FEATURES)}")
        try:
            def arr(name: str) -> np.ndarray:
                return np.asarray(ds[name].values, dtype=float)

            nets = {o: Network(arr(f"{o}_w0"), arr(f"{o}_b0"), arr(f"{o}_w1"), arr(f"{o}_b1"),
                               float(ds[f"{o}_y_mean"]), float(ds[f"{o}_y_std"]))
                    for o in OUTPUTS}
            return cls(str(ds.attrs["ship_name"]), str(ds.attrs["ship_identity"]),
                       arr("x_mean"), arr("x_std"), arr("x_lo"), arr("x_hi"),
                       nets["rpm"], nets["fuel"], float(ds.attrs["reference_draft_fore_m"]),
                       float(ds.attrs["reference_draft_aft_m"]), float(ds.attrs["fallback_std"]),
                       json.loads(ds.attrs.get("report", "{}")))
        except KeyError as exc:
            raise ModelFileError(f"{path}: learned model lacks {exc}") from exc
