"""The results of the public functions as typed mappings: one ``TypedDict`` per result, so a
type checker sees every key and its type. The keys are the tables' column names (with their SI
unit) where a table has the quantity; this module is the one place the Python package spells
them (a test compares every result's keys with these definitions).

Every key is a Python identifier (the unit suffixes are ``_m2``, ``_per_m2``, ``_N_per_m``, …);
the spectral statistics use the functional form because one of them is called ``str``. Keys
present only for some inputs (spectral statistics of complete maps, the upper body's deformation)
are not required.
"""

from __future__ import annotations

from typing import Any, Dict, List, Optional, TypedDict

import numpy as np
import numpy.typing as npt

F64 = npt.NDArray[np.float64]
I64 = npt.NDArray[np.int64]

#: The keys of the isotropic spectral moments m0 (m²), m2 and m4 (m⁻²) in :class:`SurfaceStatistics`.
MOMENT_KEYS = ("m0_m2", "m2", "m4_per_m2")

# ---------------------------------------------------------------- studies


class StudyCounts(TypedDict):
    """:func:`asperity.validate`: the study's name, its counts and its unused parameters."""

    study: str
    scenarios: int
    nodes: int
    instances: int
    unused_parameters: List[str]


# ---------------------------------------------------------------- surfaces

_SurfaceSpectral = TypedDict(
    "_SurfaceSpectral",
    {
        "m0_m2": float,
        "m2": float,
        "m4_per_m2": float,
        "m0_x_m2": float,
        "m2_x": float,
        "m4_x_per_m2": float,
        "m0_y_m2": float,
        "m2_y": float,
        "m4_y_per_m2": float,
        "gw_summit_density_per_m2": float,
        "gw_summit_radius_m": float,
        "gw_sigma_s_m": float,
        "gw_y_s_m": float,
        "gw_beta": float,
        "gw_alpha": float,
        "sal_m": float,
        "str": float,
        "correlation_length_x_m": float,
        "correlation_length_y_m": float,
        "std_rad": float,
        "hurst_fit": float,
        "hurst_fit_q_min_rad_per_m": float,
        "hurst_fit_q_max_rad_per_m": float,
        "hurst_fit_r_squared": float,
        "ssk": float,
        "sku": float,
        "sdq": float,
        "sdr_percent": float,
        "summit_mean_radius_m": float,
        "summit_height_std_m": float,
    },
    total=False,
)


_SurfaceDensity = TypedDict("_SurfaceDensity", {"summit_density_per_m2": float})


class SurfaceStatistics(_SurfaceDensity, _SurfaceSpectral):
    """The ``surfaces`` row of a map (:meth:`Topography.statistics`,
    :func:`asperity.surface_statistics`): ISO 25178-2 amplitude, hybrid, functional and volume
    parameters, and summit statistics; the spectral parameters, moments and Greenwood–Williamson
    summit statistics only for a complete map (and where defined), like the skewness, kurtosis
    and slopes of a map that has them."""

    grid_nx: int
    grid_ny: int
    dx_m: float
    dy_m: float
    missing_points: int
    sq_m: float
    sa_m: float
    sp_m: float
    sv_m: float
    sz_m: float
    sk_m: float
    spk_m: float
    svk_m: float
    smr1_percent: float
    smr2_percent: float
    sxp_m: float
    vmp_m3_per_m2: float
    vmc_m3_per_m2: float
    vvc_m3_per_m2: float
    vvv_m3_per_m2: float
    summit_count: int


class Psd(TypedDict):
    """:meth:`Topography.psd`: the radially averaged PSD, as the ``surfaces_psd`` table."""

    q_rad_per_m: F64
    c_m4: F64


class Acf(TypedDict):
    """:meth:`Topography.acf`: the radially averaged ACF, as the ``surfaces_acf`` table."""

    r_m: F64
    acf: F64


class MaterialRatio(TypedDict):
    """:meth:`Topography.material_ratio`: the material ratio curve every 1 %, as the
    ``surfaces_material_ratio`` table."""

    material_ratio_percent: F64
    height_m: F64


class Summits(TypedDict):
    """:meth:`Topography.summits`: one entry per 8-neighbour summit, as the ``surfaces_summits``
    table."""

    ix: I64
    iy: I64
    x_m: F64
    y_m: F64
    height_m: F64
    slope: F64
    radius_m: F64


#: The long tables of a surface report by name (``psd``, ``acf``, ``summits``, the material
#: ratio curve), each a mapping of column name to array.
SurfaceTables = Dict[str, Dict[str, Any]]

# ---------------------------------------------------------------- contact


class MaterialConstants(TypedDict):
    """:func:`asperity.material`: a built-in material's constants (Pa) and their source."""

    name: str
    youngs_modulus: float
    poisson_ratio: float
    hardness: Optional[float]
    flow_pressure: Optional[float]
    source: str


class LoadStep(TypedDict):
    """One load step of :class:`ContactResult` ``["load_curve"]``, as the
    ``contacts_load_curve`` table."""

    nominal_pressure_Pa: float
    area_fraction: float
    mean_contact_pressure_Pa: float
    stress_ratio: float
    plastic_area_share: float
    mean_separation_m: float
    max_elastic_deformation_m: float
    approach_m: float
    iterations: float
    residual: float


class _UpperDeformation(TypedDict, total=False):
    deformation_upper: F64


class ContactStep(_UpperDeformation):
    """One load step of :class:`ContactResult` ``["steps"]`` (``fields="all"``): its nominal
    pressure, contact area share and maps, as a study's contact node gives them to its friction
    nodes at that step."""

    nominal_pressure_Pa: float
    area_fraction: float
    pressure: F64
    gap: F64
    deformation_lower: F64
    plastic_penetration: F64


class _Steps(TypedDict, total=False):
    steps: List[ContactStep]


class ContactResult(_UpperDeformation, _Steps):
    """:func:`asperity.contact`: the ``contacts`` row of the final step, the load curve and the
    final step's fields (``deformation_upper`` with an upper surface only); with
    ``fields="all"`` also ``steps``, one :class:`ContactStep` per load step."""

    composite_modulus_Pa: float
    nominal_pressure_Pa: float
    area_fraction: float
    mean_contact_pressure_Pa: float
    stress_ratio: float
    plastic_area_share: float
    mean_separation_m: float
    max_elastic_deformation_m: float
    approach_m: float
    dx_m: float
    dy_m: float
    iterations: int
    coarse_iterations: int
    free_set_iterations: int
    residual: float
    load_curve: List[LoadStep]
    pressure: F64
    gap: F64
    deformation_lower: F64
    plastic_penetration: F64


# ---------------------------------------------------------------- friction


class FrictionLawParameter(TypedDict):
    """One parameter of a :class:`FrictionLaw`."""

    name: str
    column: str
    description: str
    kind: str
    default: Any
    unit: str
    range: str
    options: List[str]


class FrictionLaw(TypedDict):
    """:func:`asperity.friction_laws`: one law of the registry."""

    name: str
    summary: str
    basis: str
    methods: List[str]
    parameters: List[FrictionLawParameter]


class _Coefficient(TypedDict):
    mu_s: Optional[float]
    mu_s_computed: Optional[float]
    mu_s_floored: bool


class StaticFrictionRow(_Coefficient):
    """:func:`asperity.static_friction`: the result at one nominal pressure."""

    nominal_pressure_Pa: float
    friction_force_N: float
    external_load_N: float
    normal_load_N: float
    adhesion_force_N: float
    real_area_m2: float
    d_star: float
    separation_m: float
    plasticity_index: float
    contacts: float
    load_share_beyond_fit: float


class _Ploughing(TypedDict, total=False):
    """The keys a per-spot result has under a law with a deformation part (``ploughing``)."""

    ploughing_body: str
    mu_deformation_slope_baseline: float


class PerSpotResult(_Coefficient, _Ploughing):
    """:func:`asperity.per_spot_friction`: the totals and one list entry per contact spot."""

    mu_deformation: Optional[float]
    normal_load_N: float
    friction_force_N: float
    deformation_force_N: float
    real_area_m2: float
    adhesion_force_N: float
    load_share_beyond_fit: float
    load_share_without_radius: float
    load_share_merged: float
    load_share_outside_regime: float
    spot_count: int
    spots_without_radius: int
    spot_normal_force_N: List[float]
    spot_area_m2: List[float]
    spot_radius_m: List[Optional[float]]
    spot_summits: List[int]
    spot_friction_force_N: List[float]
    spot_deformation_force_N: List[float]


class PerSummitResult(_Coefficient):
    """:func:`asperity.per_summit_friction`: the totals and one list entry per summit."""

    normal_load_N: float
    adhesion_force_N: float
    friction_force_N: float
    load_share_beyond_fit: float
    summit_count: int
    summit_radius_m: List[float]
    summit_interference_m: List[float]
    summit_normal_force_N: List[float]
    summit_friction_force_N: List[float]
    summit_adhesion_force_N: List[float]
