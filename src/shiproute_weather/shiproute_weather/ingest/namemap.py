"""Names used by forecast providers, mapped onto canonical variables.

Conventions (documented per entry, converted in `normalise`):
- ECMWF IFS/ERA5 and WAM (cfgrib names): u10 v10, swh mwd mwp pp1d, shww mdww mpww, shts mdts
  mpts (total swell), mp1/mp2. ECMWF mean periods mwp/mpww/mpts are Tm-1,0 (energy period)
  and are converted to Tm01; pp1d is the peak period. Directions are "coming from".
- NOAA GFS: u10/v10 at heightAboveGround 10 (GRIB) or UGRD/VGRD, ugrd10m/vgrd10m (NOMADS).
- NOAA WAVEWATCH III model output (ww3_ounf NetCDF): hs, dir, t01/t02/t0m1, fp (peak
  frequency, Hz: Tp = 1/fp), uwnd/vwnd, ucur/vcur.
- THREDDS/NCSS NetCDF of GFS/WW3: long names with the level type, e.g.
  u-component_of_wind_height_above_ground (its height dimension: the 10 m level is taken).
- NOAA WAVEWATCH III (NOMADS GRIB/NetCDF): HTSGW, DIRPW (peak direction), PERPW (peak
  period), WVHGT WVDIR WVPER (wind sea), SWELL SWDIR SWPER (first partition = primary swell),
  WIND/WDIR or UGRD/VGRD. NOMADS NetCDF appends the level, e.g. htsgwsfc, swell_1.
  Directions are "coming from" (nautical).
- Copernicus Marine: VHM0 VMDR VTM01/VTM02/VTM10/VTPK, VHM0_WW VMDR_WW VTM01_WW, VHM0_SW1
  VMDR_SW1 VTM01_SW1; uo/vo (Eulerian) and utotal/vtotal (total incl. tides and Stokes
  drift, preferred). Directions "coming from"; currents "going to".
- CF standard_name attributes, including *_to_direction (converted by adding 180 deg).
"""

from __future__ import annotations

from dataclasses import dataclass

from ..contract import canonical as cv


@dataclass(frozen=True)
class Mapping:
    """How one source variable becomes a canonical one."""

    canonical: str
    priority: int = 0  # lower wins when several sources give the same canonical variable
    period_kind: str = "tm01"  # for periods: tm01 | tp | tm02 | tm_10 | fp (peak frequency)
    going_to: bool = False  # direction given as "going to" (add 180 deg)


def _m(canonical: str, priority: int = 0, period_kind: str = "tm01",
       going_to: bool = False) -> Mapping:
    return Mapping(canonical, priority, period_kind, going_to)


# keys are lower-case source names
NAMES: dict[str, Mapping] = {
    # wind
    "u10": _m(cv.WIND_U), "10u": _m(cv.WIND_U), "ugrd": _m(cv.WIND_U, 1),
    "ugrd10m": _m(cv.WIND_U), "ugrd_10m": _m(cv.WIND_U), "ugrdsfc": _m(cv.WIND_U, 2),
    "uwnd": _m(cv.WIND_U, 2), "u_wind": _m(cv.WIND_U, 2),
    "v10": _m(cv.WIND_V), "10v": _m(cv.WIND_V), "vgrd": _m(cv.WIND_V, 1),
    "vgrd10m": _m(cv.WIND_V), "vgrd_10m": _m(cv.WIND_V), "vgrdsfc": _m(cv.WIND_V, 2),
    "vwnd": _m(cv.WIND_V, 2), "v_wind": _m(cv.WIND_V, 2),
    # GFS served by THREDDS/NCSS: one variable per level type, height dims (10 m is picked)
    "u-component_of_wind_height_above_ground": _m(cv.WIND_U),
    "v-component_of_wind_height_above_ground": _m(cv.WIND_V),
    "u-component_of_wind_surface": _m(cv.WIND_U, 3),
    "v-component_of_wind_surface": _m(cv.WIND_V, 3),
    # WAVEWATCH III via THREDDS/NCSS
    "significant_height_of_combined_wind_waves_and_swell_surface": _m(cv.WAVE_HS),
    "primary_wave_direction_surface": _m(cv.WAVE_DIR, 2),
    "primary_wave_mean_period_surface": _m(cv.WAVE_TM, 4, "tp"),
    "significant_height_of_wind_waves_surface": _m(cv.WIND_WAVE_HS),
    "direction_of_wind_waves_surface": _m(cv.WIND_WAVE_DIR),
    "mean_period_of_wind_waves_surface": _m(cv.WIND_WAVE_TM, 1),
    "significant_height_of_swell_waves_ordered_sequence_of_data": _m(cv.SWELL_HS),
    "direction_of_swell_waves_ordered_sequence_of_data": _m(cv.SWELL_DIR),
    "mean_period_of_swell_waves_ordered_sequence_of_data": _m(cv.SWELL_TM, 1),
    # total sea
    "swh": _m(cv.WAVE_HS), "htsgw": _m(cv.WAVE_HS), "htsgwsfc": _m(cv.WAVE_HS),
    "vhm0": _m(cv.WAVE_HS), "hs": _m(cv.WAVE_HS, 1), "hm0": _m(cv.WAVE_HS, 1),
    "mwd": _m(cv.WAVE_DIR), "vmdr": _m(cv.WAVE_DIR), "dir": _m(cv.WAVE_DIR, 1),
    "dirpw": _m(cv.WAVE_DIR, 2), "dirpwsfc": _m(cv.WAVE_DIR, 2), "pwd": _m(cv.WAVE_DIR, 2),
    "mp1": _m(cv.WAVE_TM), "vtm01": _m(cv.WAVE_TM), "t01": _m(cv.WAVE_TM, 1),
    "mp2": _m(cv.WAVE_TM, 3, "tm02"), "vtm02": _m(cv.WAVE_TM, 3, "tm02"),
    "mwp": _m(cv.WAVE_TM, 2, "tm_10"), "vtm10": _m(cv.WAVE_TM, 2, "tm_10"),
    "t0m1": _m(cv.WAVE_TM, 2, "tm_10"),
    "t02": _m(cv.WAVE_TM, 3, "tm02"), "fp": _m(cv.WAVE_TM, 5, "fp"),
    "pp1d": _m(cv.WAVE_TM, 4, "tp"), "vtpk": _m(cv.WAVE_TM, 4, "tp"),
    "perpw": _m(cv.WAVE_TM, 4, "tp"), "perpwsfc": _m(cv.WAVE_TM, 4, "tp"),
    # wind sea
    "shww": _m(cv.WIND_WAVE_HS), "wvhgt": _m(cv.WIND_WAVE_HS), "wvhgtsfc": _m(cv.WIND_WAVE_HS),
    "vhm0_ww": _m(cv.WIND_WAVE_HS),
    "mdww": _m(cv.WIND_WAVE_DIR), "wvdir": _m(cv.WIND_WAVE_DIR),
    "wvdirsfc": _m(cv.WIND_WAVE_DIR), "vmdr_ww": _m(cv.WIND_WAVE_DIR),
    "vtm01_ww": _m(cv.WIND_WAVE_TM), "mpww": _m(cv.WIND_WAVE_TM, 2, "tm_10"),
    "wvper": _m(cv.WIND_WAVE_TM, 1), "wvpersfc": _m(cv.WIND_WAVE_TM, 1),
    # primary swell
    "shts": _m(cv.SWELL_HS, 1), "shps": _m(cv.SWELL_HS), "swell": _m(cv.SWELL_HS),
    "swell_1": _m(cv.SWELL_HS), "vhm0_sw1": _m(cv.SWELL_HS), "swell1": _m(cv.SWELL_HS),
    "mdts": _m(cv.SWELL_DIR, 1), "mdps": _m(cv.SWELL_DIR), "swdir": _m(cv.SWELL_DIR),
    "swdir_1": _m(cv.SWELL_DIR), "vmdr_sw1": _m(cv.SWELL_DIR), "swdir1": _m(cv.SWELL_DIR),
    "vtm01_sw1": _m(cv.SWELL_TM), "swper": _m(cv.SWELL_TM, 1), "swper_1": _m(cv.SWELL_TM, 1),
    "swper1": _m(cv.SWELL_TM, 1),
    "mpts": _m(cv.SWELL_TM, 3, "tm_10"), "mpps": _m(cv.SWELL_TM, 2, "tm_10"),
    # currents (going to)
    "utotal": _m(cv.CURRENT_U), "uo": _m(cv.CURRENT_U, 1), "ucur": _m(cv.CURRENT_U, 2),
    "uogrd": _m(cv.CURRENT_U, 2), "water_u": _m(cv.CURRENT_U, 2),
    "vtotal": _m(cv.CURRENT_V), "vo": _m(cv.CURRENT_V, 1), "vcur": _m(cv.CURRENT_V, 2),
    "vogrd": _m(cv.CURRENT_V, 2), "water_v": _m(cv.CURRENT_V, 2),
}

# CF standard names (attribute `standard_name`); priority 3 so explicit names win ties
STANDARD_NAMES: dict[str, Mapping] = {n: _m(n, 3) for n in cv.VARIABLES} | {
    "x_wind": _m(cv.WIND_U, 4), "y_wind": _m(cv.WIND_V, 4),
    "sea_surface_wave_to_direction": _m(cv.WAVE_DIR, 3, going_to=True),
    "sea_surface_wind_wave_to_direction": _m(cv.WIND_WAVE_DIR, 3, going_to=True),
    "sea_surface_swell_wave_to_direction": _m(cv.SWELL_DIR, 3, going_to=True),
    "sea_surface_primary_swell_wave_significant_height": _m(cv.SWELL_HS, 3),
    "sea_surface_primary_swell_wave_from_direction": _m(cv.SWELL_DIR, 3),
    "sea_surface_primary_swell_wave_to_direction": _m(cv.SWELL_DIR, 3, going_to=True),
    "sea_surface_primary_swell_wave_mean_period": _m(cv.SWELL_TM, 3),
    "sea_surface_wave_mean_period_from_variance_spectral_density_first_frequency_moment":
        _m(cv.WAVE_TM, 3),
    "sea_surface_wave_mean_period_from_variance_spectral_density_second_frequency_moment":
        _m(cv.WAVE_TM, 4, "tm02"),
    "sea_surface_wave_mean_period_from_variance_spectral_density_inverse_frequency_moment":
        _m(cv.WAVE_TM, 4, "tm_10"),
    "sea_surface_wave_period_at_variance_spectral_density_maximum": _m(cv.WAVE_TM, 5, "tp"),
    "sea_surface_wind_wave_mean_period_from_variance_spectral_density_first_frequency_moment":
        _m(cv.WIND_WAVE_TM, 3),
    "sea_surface_swell_wave_mean_period_from_variance_spectral_density_first_frequency_moment":
        _m(cv.SWELL_TM, 3),
    "surface_eastward_sea_water_velocity": _m(cv.CURRENT_U, 3),
    "surface_northward_sea_water_velocity": _m(cv.CURRENT_V, 3),
}

# speed + direction pairs turned into u/v: (speed names, direction names, going_to)
WIND_SPEED_NAMES = ("wind", "ws", "wind_speed", "si10", "windsfc", "wind10m")
WIND_DIR_NAMES = ("wdir", "wind_from_direction", "wdir10", "wdirsfc")
CURRENT_SPEED_NAMES = ("sea_water_speed", "cspd", "current_speed")
CURRENT_DIR_NAMES = ("direction_of_sea_water_velocity", "cdir", "current_direction")


def lookup(name: str, standard_name: str | None) -> Mapping | None:
    """Mapping for a source variable by its name, else by its CF standard_name."""
    m = NAMES.get(name.lower())
    if m is None and name.lower() in cv.VARIABLES:
        m = _m(name.lower(), 3)
    if m is None and standard_name:
        m = STANDARD_NAMES.get(standard_name.strip().lower())
    return m
