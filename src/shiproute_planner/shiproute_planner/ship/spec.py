"""Frozen description of one ship in one loading condition (SI units, names carry units)."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class HullSpec:
    """Hull-form data used by Holtrop-Mennen, STAWAVE-2 and the box-hull seakeeping model."""

    lpp_m: float
    lwl_m: float
    breadth_m: float
    depth_m: float
    midship_coefficient: float
    waterplane_coefficient: float
    lcb_percent: float  # longitudinal centre of buoyancy, % of Lwl forward of 0.5 Lwl
    stern_shape_coefficient: float  # Holtrop-Mennen C_stern (-25 pram .. +10 U-shaped)
    bulb_area_m2: float
    bulb_center_height_m: float
    transom_area_m2: float
    appendage_area_m2: float
    appendage_form_factor: float  # (1 + k2)
    wetted_surface_m2: float | None  # None: Holtrop-Mennen estimate
    pitch_gyradius_ratio: float  # k_yy / Lpp
    bow_height_m: float  # height of the weather deck at the fore perpendicular above keel


@dataclass(frozen=True)
class PropellerSpec:
    """Wageningen B-series fixed-pitch propeller."""

    blades: int
    diameter_m: float
    pitch_ratio: float
    area_ratio: float
    shaft_center_height_m: float
    shaft_efficiency: float


@dataclass(frozen=True)
class EngineSpec:
    """Two-stroke main engine: rating, speed range, limits and SFOC curve."""

    mcr_kw: float
    rpm_mcr: float
    rpm_min: float
    rpm_max: float
    overload_power_fraction: float  # allowed brake power / MCR before the limit is reported
    torque_limit_fraction: float  # allowed torque / torque at MCR
    sfoc_load_fraction: tuple[float, ...]
    sfoc_g_per_kwh: tuple[float, ...]


@dataclass(frozen=True)
class WindageSpec:
    """Above-water projected areas and the longitudinal wind-resistance coefficient C_AA(angle)."""

    frontal_area_m2: float
    lateral_area_m2: float
    coefficient_set: str
    relative_angle_deg: tuple[float, ...]  # 0 = head wind .. 180 = following wind
    caa: tuple[float, ...]  # resistance coefficient (positive = resists forward motion)


@dataclass(frozen=True)
class LoadingCondition:
    """One loading condition: drafts, displacement and transverse stability."""

    name: str
    draft_fore_m: float
    draft_aft_m: float
    displacement_t: float
    gm_m: float
    roll_period_s: float | None  # None: IMO IS Code estimate from GM
    bulb_area_m2: float | None = None  # immersed bulb section at this draft (None: hull's)
    bulb_center_height_m: float | None = None


@dataclass(frozen=True)
class SeakeepingSpec:
    """Operational limits and seakeeping criteria (probabilities per wave encounter)."""

    max_hs_m: float
    max_wind_m_s: float
    slamming_probability: float
    deck_wetness_probability: float
    propeller_emergence_probability: float
    roll_resonance_tolerance: float  # relative |Te - T_res| / T_res that counts as resonance
    min_hs_imo_check_m: float  # minimum Hs for the MSC.1/Circ.1228 flags


@dataclass(frozen=True)
class WaterSpec:
    """Sea water for density and viscosity (constant along a voyage)."""

    temperature_c: float
    salinity_psu: float


@dataclass(frozen=True)
class ShipSpec:
    """A ship file resolved for one loading condition."""

    name: str
    description: str
    ship_type: str  # container | tanker | bulk | general
    hull: HullSpec
    propeller: PropellerSpec
    engine: EngineSpec
    windage: WindageSpec
    condition: LoadingCondition
    conditions: tuple[str, ...]
    seakeeping: SeakeepingSpec
    water: WaterSpec
    sources: tuple[str, ...]
    content_hash: str  # sha256 of the file text + condition; keys caches of derived models
    # planner model the file asks for: "" (physics), "kwon", "profile:PATH" or "learned:PATH";
    # relative paths resolved against the ship file's folder
    performance_model: str = ""
    # fuel_type and economics entries as (key, value) pairs (`ship.fuel.parse_economics`)
    economics: tuple[tuple[str, object], ...] = ()

    @property
    def mean_draft_m(self) -> float:
        """Mean draft of the loading condition."""
        return 0.5 * (self.condition.draft_fore_m + self.condition.draft_aft_m)
