"""Type stubs of the compiled module; the public, documented API is `asperity` (__init__.py)."""

from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

F64 = npt.NDArray[np.float64]

TOOL_VERSION: str
DEFAULT_TOLERANCE: float
DEFAULT_ADHESION_ENERGY: float
DEFAULT_EQUILIBRIUM_DISTANCE: float
MATERIAL_RATIO_TABLE: str
DIMENSIONS: Dict[str, Tuple[str, str, str]]

class StudyError(Exception):
    file: str
    line: Optional[int]
    column: Optional[int]
    context: str
    message: str

def run_study(
    study: str,
    set: Sequence[str] = ...,
    out: Optional[str] = ...,
    cache: Optional[str] = ...,
    jobs: Optional[int] = ...,
    memory_mib: Optional[int] = ...,
    progress: Optional[Callable[[str, Any, str], None]] = ...,
    force: bool = ...,
) -> Tuple[str, List[str], Dict[str, Any]]: ...
def plan_study(study: str, set: Sequence[str] = ..., cache: Optional[str] = ...) -> List[Dict[str, Any]]: ...
def validate_study(study: str, set: Sequence[str] = ...) -> Dict[str, Any]: ...
def parse_quantity(parameter: str, text: str, dimension_name: str) -> float: ...
def is_column_name(name: str) -> bool: ...
def list_column(name: str) -> Optional[str]: ...
def topography_format(path: str) -> Optional[str]: ...
def read_topography(
    path: str,
    pixel_size: Optional[Tuple[float, float]] = ...,
    size: Optional[Tuple[float, float]] = ...,
    override_file_spacing: bool = ...,
    channel: Optional[str] = ...,
    height_unit: Optional[float] = ...,
) -> Dict[str, Any]: ...
def surface_report(
    heights: F64, dx: float, dy: float, periodic: bool = ...
) -> Tuple[Dict[str, Any], Dict[str, Dict[str, Any]], List[str]]: ...
def scale_checks(heights: F64, dx: float, dy: float, periodic: bool = ...) -> Tuple[Optional[float], List[str]]: ...
def remove_form(heights: F64, dx: float, dy: float, degree: int) -> Tuple[F64, float]: ...
def gaussian_filter(
    heights: F64, dx: float, dy: float, kind: str, cutoff: float, long_cutoff: Optional[float] = ...
) -> F64: ...
def fill_missing(heights: F64, dx: float, dy: float) -> Tuple[F64, int]: ...
def synthetic_surface(
    grid: Tuple[int, int],
    size: Tuple[float, float],
    sq: float,
    hurst: float,
    correlation_length: float,
    seed: int,
    short_wavelength_cutoff: Optional[float] = ...,
    anisotropy: Optional[Tuple[float, float]] = ...,
) -> Tuple[F64, float, float]: ...
def synthetic_twin(
    measured: Sequence[Tuple[F64, float, float]],
    sq: float,
    grid: Tuple[int, int],
    size: Tuple[float, float],
    seed: int,
    short_wavelength_cutoff: Optional[float] = ...,
    threshold: float = ...,
) -> Tuple[F64, float, float, Dict[str, Any]]: ...
def spectrum_twin(
    measured: Sequence[Tuple[F64, float, float]],
    sq: Optional[float],
    grid: Optional[Tuple[int, int]],
    size: Optional[Tuple[float, float]],
    seed: int,
    short_wavelength_cutoff: Optional[float] = ...,
    extrapolation: str = ...,
) -> Tuple[F64, float, float, Dict[str, Any]]: ...
def material(name: str) -> Dict[str, Any]: ...
def contact(
    lower: F64,
    dx: float,
    dy: float,
    lower_body: Tuple[float, float],
    nominal_pressures: Sequence[float],
    flow_pressure: float,
    upper: Optional[F64] = ...,
    upper_body: Optional[Tuple[float, float]] = ...,
    periodic: bool = ...,
    tolerance: Optional[float] = ...,
    slopes: Sequence[float] = ...,
    all_steps: bool = ...,
) -> Tuple[Dict[str, Any], List[str]]: ...
def friction_laws() -> List[Dict[str, Any]]: ...
def static_friction(
    model: str,
    composite_modulus: float,
    hardness: float,
    poisson_ratio: float,
    nominal_pressures: Sequence[float],
    nominal_area: float,
    moments: Optional[Tuple[float, float, float]] = ...,
    summits_explicit: Optional[Tuple[float, float, float]] = ...,
    adhesion_energy: float = ...,
    equilibrium_distance: float = ...,
    parameters: Mapping[str, Union[float, str]] = ...,
    yield_strength: Optional[float] = ...,
    shear_strength: Optional[float] = ...,
) -> List[Dict[str, Any]]: ...
def per_summit_friction(
    composite_height: F64,
    pressure: F64,
    gap: F64,
    deformation: F64,
    plastic_penetration: F64,
    dx: float,
    dy: float,
    model: str,
    composite_modulus: float,
    hardness: float,
    poisson_ratio: float,
    periodic: bool = ...,
    adhesion_energy: float = ...,
    equilibrium_distance: float = ...,
    parameters: Mapping[str, Union[float, str]] = ...,
    yield_strength: Optional[float] = ...,
) -> Dict[str, Any]: ...
def per_spot_friction(
    pressure: F64,
    gap: F64,
    composite_height: F64,
    deformation_lower: F64,
    plastic_penetration: F64,
    dx: float,
    dy: float,
    model: str,
    lower_body: Tuple[float, float, float],
    upper_body: Optional[Tuple[float, float, float]] = ...,
    upper_height: Optional[F64] = ...,
    deformation_upper: Optional[F64] = ...,
    periodic: bool = ...,
    eight_connected: bool = ...,
    adhesion_energy: float = ...,
    equilibrium_distance: float = ...,
    parameters: Mapping[str, Union[float, str]] = ...,
    yield_strength: Optional[float] = ...,
    shear_strength: Optional[float] = ...,
) -> Dict[str, Any]: ...
