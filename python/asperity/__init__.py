"""asperity: reproducible rough-surface contact and static-friction studies, from Python.

Studies: :func:`run`, :func:`plan`, :func:`validate` (a broken study raises :class:`StudyError`).
Numerics on NumPy arrays, SI units throughout (metres, pascals): :func:`read_topography`,
:func:`surface_statistics`, :func:`remove_form`, :func:`gaussian_filter`, :func:`fill_missing`,
:func:`synthetic_surface`, :func:`synthetic_twin`, :func:`contact`, :func:`material`,
:func:`static_friction`, :func:`per_spot_friction`.

Every computation releases the GIL; a bad argument raises ``TypeError`` or ``ValueError`` naming
the parameter and its expected unit or range.
"""

from __future__ import annotations

import os
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _native
from ._native import StudyError

__all__ = [
    "StudyError",
    "RunResult",
    "run",
    "plan",
    "validate",
    "read_topography",
    "topography_format",
    "surface_statistics",
    "remove_form",
    "gaussian_filter",
    "fill_missing",
    "synthetic_surface",
    "synthetic_twin",
    "material",
    "contact",
    "static_friction",
    "per_spot_friction",
]

__version__ = _native.TOOL_VERSION

PathLike = Union[str, "os.PathLike[str]"]
Progress = Callable[[str, Any, str], None]
Material = Union[str, Mapping[str, float]]


# ---------------------------------------------------------------- argument checks


def _path(name: str, value: Any) -> str:
    if isinstance(value, (str, os.PathLike)):
        return os.fspath(value)
    raise TypeError(f"{name}: expected a path (str or os.PathLike), got {type(value).__name__}")


def _optional_path(name: str, value: Any) -> Optional[str]:
    return None if value is None else _path(name, value)


def _number(name: str, value: Any, unit: str, *, positive: bool = True) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name}: expected a number in {unit}, got {type(value).__name__}")
    x = float(value)
    if not np.isfinite(x) or (positive and x <= 0.0):
        raise ValueError(f"{name}: {x!r} {unit} is out of range: must be finite and > 0 {unit}")
    return x


def _integer(name: str, value: Any, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name}: expected an integer >= {minimum}, got {type(value).__name__}")
    if int(value) < minimum:
        raise ValueError(f"{name}: {int(value)} is out of range: must be >= {minimum}")
    return int(value)


def _pair(name: str, value: Any, unit: str) -> Tuple[float, float]:
    if isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool):
        x = _number(name, value, unit)
        return (x, x)
    if isinstance(value, (tuple, list, np.ndarray)) and len(value) == 2:
        return (_number(f"{name}[0]", value[0], unit), _number(f"{name}[1]", value[1], unit))
    raise TypeError(f"{name}: expected a number or a pair (x, y) in {unit}, got {value!r}")


def _heights(name: str, value: Any) -> np.ndarray:
    if not isinstance(value, np.ndarray):
        raise TypeError(f"{name}: expected a 2-D NumPy array of heights in m, got {type(value).__name__}")
    if value.ndim != 2:
        raise ValueError(f"{name}: expected a 2-D array [iy, ix] of heights in m, got {value.ndim} dimension(s)")
    if value.dtype.kind not in "fiu":
        raise TypeError(f"{name}: expected real heights in m, got dtype {value.dtype}")
    return np.ascontiguousarray(value, dtype=np.float64)


def _spacing(dx: Any, dy: Any) -> Tuple[float, float]:
    x = _number("dx", dx, "m")
    return x, (x if dy is None else _number("dy", dy, "m"))


def _set(set: Union[None, Mapping[str, Any], Sequence[str]]) -> List[str]:
    """Overrides as the command line's ``--set NAME=VALUE`` strings."""
    if set is None:
        return []
    if isinstance(set, Mapping):
        return [f"{k}={_override_value(v)}" for k, v in set.items()]
    if isinstance(set, str):
        return [set]
    if isinstance(set, Sequence) and all(isinstance(s, str) for s in set):
        return list(set)
    raise TypeError("set: expected a mapping {name: value} or a list of 'name=value' strings")


def _override_value(v: Any) -> str:
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(str(x) for x in v) + "]"
    return str(v)


# ---------------------------------------------------------------- studies


@dataclass
class RunResult:
    """The tables a run wrote (polars DataFrames by table name), its folder and its counts."""

    folder: Path
    tables: Dict[str, Any]
    computed: int
    cached: int
    failed: int
    skipped: int
    flagged: int
    wall_seconds: float
    failures: List[Tuple[str, str, str]] = field(default_factory=list)
    flags: List[Tuple[str, str, str]] = field(default_factory=list)

    def __getitem__(self, table: str) -> Any:
        return self.tables[table]


def _text_progress() -> Progress:
    state = {"total": 0, "done": 0}

    def show(event: str, a: Any, b: str) -> None:
        if event == "start":
            state["total"] = int(a)
        elif event == "node":
            state["done"] += 1
            end = "\n" if state["done"] == state["total"] else ""
            sys.stderr.write(f"\r{state['done']}/{state['total']} nodes  {a:<9} {b[:60]:<60}{end}")
            sys.stderr.flush()
        elif event == "warning":
            import warnings

            warnings.warn(str(a), stacklevel=2)

    return show


def run(
    study: PathLike,
    set: Union[None, Mapping[str, Any], Sequence[str]] = None,
    out: Optional[PathLike] = None,
    cache: Optional[PathLike] = None,
    jobs: Optional[int] = None,
    *,
    memory_mib: Optional[int] = None,
    progress: Union[bool, Progress, None] = None,
) -> RunResult:
    """Run a study as ``asperity run`` does and return its tables as polars DataFrames.

    ``set`` overrides parameter axes (``{"sq": ["0.4 um", "1 um"]}`` or ``["n=64"]``); ``out``
    is the results folder (default ``results/<study>``), ``cache`` the cache folder (default
    ``$ASPERITY_CACHE`` or ``./cache``), ``jobs`` the worker threads (default all cores).
    ``progress=True`` shows a progress line on stderr; a callable receives
    ``(event, value, text)`` with events ``"start"`` (total), ``"node"`` (status, node) and
    ``"warning"`` (message). Ctrl-C stops the run after the nodes being computed (the cache
    stays valid, no tables are written) and raises ``KeyboardInterrupt``.
    """
    import polars as pl

    callback = _text_progress() if progress is True else (progress or None)
    if callback is not None and not callable(callback):
        raise TypeError("progress: expected True, False, None or a callable(event, value, text)")
    if jobs is not None:
        jobs = _integer("jobs", jobs, 1)
    if memory_mib is not None:
        memory_mib = _integer("memory_mib", memory_mib, 1)
    folder, files, report = _native.run_study(
        _path("study", study),
        _set(set),
        _optional_path("out", out),
        _optional_path("cache", cache),
        jobs,
        memory_mib,
        callback,
    )
    tables = {Path(f).stem: pl.read_parquet(f) for f in files if str(f).endswith(".parquet")}
    return RunResult(
        folder=Path(folder),
        tables=tables,
        computed=report["computed"],
        cached=report["cached"],
        failed=report["failed"],
        skipped=report["skipped"],
        flagged=report["flagged"],
        wall_seconds=report["wall_seconds"],
        failures=list(report["failures"]),
        flags=list(report["flags"]),
    )


def plan(
    study: PathLike,
    set: Union[None, Mapping[str, Any], Sequence[str]] = None,
    cache: Optional[PathLike] = None,
) -> Any:
    """The instances a run would load or compute, as a polars DataFrame
    (``key``, ``kind``, ``version``, ``nodes``, ``cached``)."""
    import polars as pl

    rows = _native.plan_study(_path("study", study), _set(set), _optional_path("cache", cache))
    schema = {"key": pl.Utf8, "kind": pl.Utf8, "version": pl.UInt32, "nodes": pl.List(pl.Utf8), "cached": pl.Boolean}
    return pl.DataFrame(rows, schema=schema)


def validate(study: PathLike, set: Union[None, Mapping[str, Any], Sequence[str]] = None) -> Dict[str, Any]:
    """Check a study without running it: its name and counts of scenarios, nodes and instances,
    and the parameters no node uses. A broken study raises :class:`StudyError`."""
    return dict(_native.validate_study(_path("study", study), _set(set)))


# ---------------------------------------------------------------- surfaces


def topography_format(path: PathLike) -> Optional[str]:
    """The reader asperity would use for ``path`` (magic bytes, then extension), or None."""
    return _native.topography_format(_path("path", path))


def read_topography(
    path: PathLike,
    pixel_size: Union[None, float, Tuple[float, float]] = None,
    size: Union[None, float, Tuple[float, float]] = None,
    *,
    override_file_spacing: bool = False,
) -> Dict[str, Any]:
    """Read a topography file (every format of ``asperity inspect``).

    Returns a dict: ``heights`` (m, ``[iy, ix]``, missing points NaN), ``dx``/``dy`` (m; a line
    scan has ``x`` positions in m instead), ``spacing_from_file``, ``height_unit_from_file``,
    ``channel`` and ``metadata``. The spacing is never guessed: a file that does not state it
    needs ``pixel_size`` (dx, dy in m) or ``size`` (Lx, Ly of the whole map in m); one that
    does must agree with them unless ``override_file_spacing``.
    """
    return dict(
        _native.read_topography(
            _path("path", path),
            None if pixel_size is None else _pair("pixel_size", pixel_size, "m"),
            None if size is None else _pair("size", size, "m"),
            bool(override_file_spacing),
        )
    )


def surface_statistics(heights: np.ndarray, dx: float, dy: Optional[float] = None, *, periodic: bool = False) -> Dict[str, Any]:
    """The statistics of the ``surfaces`` table for a height map (m, NaN missing) at spacing
    ``dx``, ``dy`` (m): ISO 25178-2 amplitude and hybrid parameters, spectral parameters (Sal,
    Str, Std, Hurst, moments; complete maps only) and summit statistics, keyed by column name
    with the SI unit (``sq_m``, ``sdq``, ``m2``…). ``periodic`` for synthetic (periodic) maps."""
    x, y = _spacing(dx, dy)
    return dict(_native.surface_statistics(_heights("heights", heights), x, y, bool(periodic)))


def remove_form(heights: np.ndarray, dx: float, dy: Optional[float] = None, *, degree: int = 1) -> Tuple[np.ndarray, float]:
    """Remove the least-squares Legendre polynomial form of total degree ``degree`` (1: plane);
    returns the residual heights (m) and their rms (m)."""
    x, y = _spacing(dx, dy)
    return _native.remove_form(_heights("heights", heights), x, y, _integer("degree", degree, 0))


def gaussian_filter(
    heights: np.ndarray,
    dx: float,
    dy: Optional[float] = None,
    *,
    kind: str,
    cutoff: float,
    long_cutoff: Optional[float] = None,
) -> np.ndarray:
    """ISO 16610-61 areal Gaussian filter: ``kind="low"`` (S-filter, λs = ``cutoff``),
    ``"high"`` (L-filter, λc = ``cutoff``) or ``"band"`` (λs = ``cutoff``, λc = ``long_cutoff``);
    cut-off wavelengths in m."""
    x, y = _spacing(dx, dy)
    long = None if long_cutoff is None else _number("long_cutoff", long_cutoff, "m")
    return _native.gaussian_filter(_heights("heights", heights), x, y, str(kind), _number("cutoff", cutoff, "m"), long)


def fill_missing(heights: np.ndarray, dx: float, dy: Optional[float] = None) -> Tuple[np.ndarray, int]:
    """Fill the missing (NaN) points by harmonic interpolation of the measured ones; returns the
    heights (m) and the number of points filled."""
    x, y = _spacing(dx, dy)
    return _native.fill_missing(_heights("heights", heights), x, y)


def synthetic_surface(
    grid: Union[int, Tuple[int, int]],
    size: Union[float, Tuple[float, float]],
    *,
    sq: float,
    hurst: float,
    correlation_length: float,
    seed: int = 1,
    short_wavelength_cutoff: Optional[float] = None,
    anisotropy: Optional[Tuple[float, float]] = None,
) -> Tuple[np.ndarray, float, float]:
    """A periodic self-affine Gaussian surface, the one a study's ``synthetic`` surface with the
    same parameters makes: ``grid`` points (nx, ny), ``size`` (Lx, Ly in m), ``sq`` (m), Hurst
    exponent in (0, 1], roll-off ``correlation_length`` (m), optional ``anisotropy``
    (aspect ratio, lay angle in rad). Returns ``(heights, dx, dy)``."""
    nx, ny = (grid, grid) if isinstance(grid, (int, np.integer)) else grid
    return _native.synthetic_surface(
        (_integer("grid[0]", nx, 2), _integer("grid[1]", ny, 2)),
        _pair("size", size, "m"),
        _number("sq", sq, "m"),
        _number("hurst", hurst, "1"),
        _number("correlation_length", correlation_length, "m"),
        _integer("seed", seed, 0),
        None if short_wavelength_cutoff is None else _number("short_wavelength_cutoff", short_wavelength_cutoff, "m"),
        None if anisotropy is None else (_number("anisotropy[0]", anisotropy[0], "1"), _number("anisotropy[1]", anisotropy[1], "rad", positive=False)),
    )


def synthetic_twin(
    measured: Sequence[Tuple[np.ndarray, float, float]],
    *,
    sq: Union[float, str],
    grid: Union[None, int, Tuple[int, int]] = None,
    size: Union[None, float, Tuple[float, float]] = None,
    seed: int = 1,
    short_wavelength_cutoff: Optional[float] = None,
    threshold: float = 0.2,
    spectrum: str = "self_affine",
    extrapolation: str = "zero",
) -> Tuple[np.ndarray, float, float, Dict[str, Any]]:
    """A synthetic twin of measured surfaces (complete maps ``(heights, dx, dy)``, m) on ``grid``
    over ``size`` (m), at Sq ``sq`` (m, or ``"measured"``). Returns ``(heights, dx, dy, info)``.

    ``spectrum="self_affine"`` (default): their texture (correlation lengths at ACF ``threshold``,
    Hurst exponent) fitted against Sq and predicted at ``sq`` (``"measured"``: the maps'
    geometric mean Sq); ``grid`` and ``size`` are required.

    ``spectrum="measured"``: their measured 2-D power spectrum itself (Hann-window periodogram,
    averaged over the maps and interpolated onto the twin's wavevectors) with random phases
    from ``seed``, scaled to ``sq`` (``"measured"``: the maps' quadratic mean Sq); ``grid`` and
    ``size`` default to the first map's. ``extrapolation`` fills the wavelengths shorter than
    the maps' sampling: ``"zero"`` or ``"power_law"`` (each map's power law over the widest band
    where its radial PSD is one, between 2 pixels and half its shorter side). The same numerics
    as a study's ``twin: {spectrum: measured}``."""
    maps = [(_heights(f"measured[{i}]", h), *_spacing(dx, dy)) for i, (h, dx, dy) in enumerate(measured)]
    nx_ny = None if grid is None else ((grid, grid) if isinstance(grid, (int, np.integer)) else grid)
    checked_grid = None if nx_ny is None else (_integer("grid[0]", nx_ny[0], 2), _integer("grid[1]", nx_ny[1], 2))
    checked_size = None if size is None else _pair("size", size, "m")
    cutoff = None if short_wavelength_cutoff is None else _number("short_wavelength_cutoff", short_wavelength_cutoff, "m")
    target = None if isinstance(sq, str) and sq == "measured" else _number("sq", sq, "m")
    if spectrum == "measured":
        if not isinstance(extrapolation, str):
            raise TypeError(f"extrapolation: expected 'zero' or 'power_law', got {type(extrapolation).__name__}")
        return _native.spectrum_twin(maps, target, checked_grid, checked_size, _integer("seed", seed, 0), cutoff, extrapolation)
    if spectrum != "self_affine":
        raise ValueError(f"spectrum: expected 'self_affine' or 'measured', got {spectrum!r}")
    if extrapolation != "zero":
        raise ValueError("extrapolation: applies to spectrum='measured' only")
    if checked_grid is None or checked_size is None:
        raise ValueError("grid, size: required for a self-affine twin (spectrum='measured' defaults to the first map's)")
    if target is None:
        sqs = [float(np.sqrt(np.mean((h - h.mean()) ** 2))) for h, _, _ in maps]
        target = float(np.exp(np.mean(np.log(sqs)))) if sqs else 1.0
    return _native.synthetic_twin(
        maps,
        target,
        checked_grid,
        checked_size,
        _integer("seed", seed, 0),
        cutoff,
        _number("threshold", threshold, "1"),
    )


# ---------------------------------------------------------------- contact


def material(name: str) -> Dict[str, Any]:
    """A built-in material (case-insensitive name or alias): ``youngs_modulus`` (Pa),
    ``poisson_ratio``, ``hardness`` (Pa), ``flow_pressure`` (Pa) and ``source``."""
    if not isinstance(name, str):
        raise TypeError(f"material: expected a material name, got {type(name).__name__}")
    return dict(_native.material(name))


def _body(name: str, m: Material) -> Tuple[Tuple[float, float], Optional[float]]:
    """(E, ν) and the flow pressure (Pa, or None) of a material name or mapping."""
    if isinstance(m, str):
        d: Mapping[str, Any] = _native.material(m)
    elif isinstance(m, Mapping):
        d = m
    else:
        raise TypeError(f"{name}: expected a material name or a mapping with youngs_modulus (Pa) and poisson_ratio")
    for key in ("youngs_modulus", "poisson_ratio"):
        if key not in d:
            raise ValueError(f"{name}: missing '{key}'")
    nu = d["poisson_ratio"]
    if isinstance(nu, bool) or not isinstance(nu, (int, float, np.integer, np.floating)) or not (0.0 <= float(nu) < 0.5):
        raise ValueError(f"{name}.poisson_ratio: {nu!r} is out of range: expected 0 <= ν < 0.5")
    flow = d.get("flow_pressure")
    return (
        (_number(f"{name}.youngs_modulus", d["youngs_modulus"], "Pa"), float(nu)),
        None if flow is None else _number(f"{name}.flow_pressure", flow, "Pa"),
    )


def contact(
    lower: np.ndarray,
    dx: float,
    dy: Optional[float] = None,
    *,
    nominal_pressures: Union[float, Sequence[float]],
    lower_material: Material,
    upper: Optional[np.ndarray] = None,
    upper_material: Optional[Material] = None,
    flow_pressure: Optional[float] = None,
    periodic: bool = True,
    tolerance: Optional[float] = None,
) -> Dict[str, Any]:
    """Elastic–perfectly-plastic FFT boundary-element contact, as a study's ``contact`` node.

    ``lower`` (and ``upper``) are height maps (m) at spacing ``dx``, ``dy`` (m); without
    ``upper`` the counter-body is a rigid flat. Materials are built-in names or mappings
    ``{youngs_modulus: Pa, poisson_ratio, flow_pressure: Pa (optional)}``; the flow pressure
    p_lim is ``flow_pressure``, else the smaller of the materials', else infinite (elastic).
    ``nominal_pressures`` (Pa, ascending, below p_lim) are solved as load steps; ``periodic``
    surfaces wrap around, otherwise the DC-FFT of a finite patch is used; ``tolerance`` is the
    relative error of every convergence condition.

    Returns a dict: the ``contacts`` row of the final step (``area_fraction``,
    ``mean_contact_pressure_Pa``, ``mean_separation_m``, ``approach_m``, ``iterations``,
    ``residual``, …), ``load_curve`` (one dict per step) and the final step's arrays
    ``pressure`` (Pa), ``gap`` (m), ``deformation_lower``/``deformation_upper`` (m) and
    ``plastic_penetration`` (m).
    """
    x, y = _spacing(dx, dy)
    low = _heights("lower", lower)
    up = None if upper is None else _heights("upper", upper)
    if up is not None and up.shape != low.shape:
        raise ValueError(f"upper: shape {up.shape} differs from lower's {low.shape}")
    lower_body, lower_flow = _body("lower_material", lower_material)
    upper_body, upper_flow = (None, None) if upper_material is None else _body("upper_material", upper_material)
    if flow_pressure is not None:
        p_lim = _number("flow_pressure", flow_pressure, "Pa")
    else:
        flows = [f for f in (lower_flow, upper_flow if up is not None else None) if f is not None]
        p_lim = min(flows) if flows else float("inf")
    pressures = [nominal_pressures] if np.isscalar(nominal_pressures) else list(nominal_pressures)
    pressures = [_number(f"nominal_pressures[{i}]", p, "Pa") for i, p in enumerate(pressures)]
    tol = None if tolerance is None else _number("tolerance", tolerance, "1")
    return dict(
        _native.contact(low, x, y, lower_body, pressures, p_lim, up, upper_body, bool(periodic), tol)
    )


# ---------------------------------------------------------------- friction


def _friction_material(material: Optional[Material], composite_modulus: Any, hardness: Any, poisson_ratio: Any) -> Tuple[float, float, float]:
    """E* (Pa), H (Pa) and ν of a body against a rigid flat: from a material (E* = E/(1 − ν²)) or
    as given."""
    if material is not None:
        if any(v is not None for v in (composite_modulus, hardness, poisson_ratio)):
            raise ValueError("material: give a material or composite_modulus/hardness/poisson_ratio, not both")
        d = _native.material(material) if isinstance(material, str) else material
        (e, nu), _ = _body("material", d)
        if d.get("hardness") is None:
            raise ValueError("material: needs a hardness (Pa)")
        composite_modulus, hardness, poisson_ratio = e / (1.0 - nu * nu), d["hardness"], nu
    if composite_modulus is None or hardness is None or poisson_ratio is None:
        raise ValueError("material: give a material, or composite_modulus, hardness and poisson_ratio")
    return (
        _number("composite_modulus", composite_modulus, "Pa"),
        _number("hardness", hardness, "Pa"),
        _number("poisson_ratio", poisson_ratio, "1", positive=False),
    )


def static_friction(
    *,
    model: str,
    nominal_pressures: Union[float, Sequence[float]],
    nominal_area: float,
    material: Optional[Material] = None,
    composite_modulus: Optional[float] = None,
    hardness: Optional[float] = None,
    poisson_ratio: Optional[float] = None,
    moments: Optional[Tuple[float, float, float]] = None,
    summits: Optional[Tuple[float, float, float]] = None,
    adhesion_energy: Optional[float] = None,
    equilibrium_distance: Optional[float] = None,
    parameters: Optional[Mapping[str, Union[float, str]]] = None,
    yield_strength: Optional[float] = None,
    shear_strength: Optional[float] = None,
) -> List[Dict[str, Any]]:
    """Statistical static friction coefficient μ_s of a rough surface against a rigid flat, as a
    study's statistical ``friction`` node computes it. ``model`` is a law of the registry with
    single-asperity laws (``"kogut_etsion"``, ``"chang_etsion_bogy"``, ``"full_stick"``, …;
    equations in docs/friction-models.md), ``parameters`` overrides its parameters (SI numbers or
    choices by name); ``yield_strength`` Y (default Tabor's H/2.8) and ``shear_strength`` k
    (default Y/√3) are the softer body's, in Pa.

    Roughness: the isotropic spectral ``moments`` (m0 in m², m2, m4 in 1/m², as
    :func:`surface_statistics` reports them), or ``summits`` (σ_s in m, radius R in m, density
    η in 1/m²). Material: a built-in name or mapping (``youngs_modulus``, ``poisson_ratio``,
    ``hardness``; the composite modulus against a rigid flat is E/(1 − ν²)), or the explicit
    ``composite_modulus``, ``hardness`` (Pa) and ``poisson_ratio``. Loads: ``nominal_pressures``
    (Pa) over ``nominal_area`` (m²). Adhesion: Δγ in N/m and ε in m (defaults as in a study).

    Returns one dict per pressure: ``mu_s`` (None at a non-compressive load), the contact and
    friction forces (N), real contact area (m²), d*, plasticity index, contacting summits and
    the load beyond the friction law's validated range.
    """
    composite_modulus, hardness, poisson_ratio = _friction_material(material, composite_modulus, hardness, poisson_ratio)
    pressures = [nominal_pressures] if np.isscalar(nominal_pressures) else list(nominal_pressures)
    triple = lambda name, t, units: None if t is None else tuple(  # noqa: E731
        _number(f"{name}[{i}]", v, u) for i, (v, u) in enumerate(zip(t, units))
    )
    return _native.static_friction(
        str(model),
        composite_modulus,
        hardness,
        poisson_ratio,
        [_number(f"nominal_pressures[{i}]", p, "Pa") for i, p in enumerate(pressures)],
        _number("nominal_area", nominal_area, "m^2"),
        triple("moments", moments, ("m^2", "1", "1/m^2")),
        triple("summits", summits, ("m", "m", "1/m^2")),
        _native.DEFAULT_ADHESION_ENERGY if adhesion_energy is None else _number("adhesion_energy", adhesion_energy, "N/m", positive=False),
        _native.DEFAULT_EQUILIBRIUM_DISTANCE if equilibrium_distance is None else _number("equilibrium_distance", equilibrium_distance, "m"),
        *_law_options(parameters, yield_strength, shear_strength),
    )


def _law_options(parameters: Any, yield_strength: Any, shear_strength: Any) -> Tuple[Dict[str, Any], Optional[float], Optional[float]]:
    """A law's parameter overrides and the softer body's strengths (Pa), checked."""
    if parameters is None:
        parameters = {}
    if not isinstance(parameters, Mapping) or not all(isinstance(k, str) for k in parameters):
        raise TypeError("parameters: expected a mapping {name: number or choice}")
    for name, v in parameters.items():
        if isinstance(v, bool) or not isinstance(v, (int, float, str, np.integer, np.floating)):
            raise TypeError(f"parameters.{name}: expected a number (SI) or a choice's name, got {type(v).__name__}")
    return (
        {k: (v if isinstance(v, str) else float(v)) for k, v in parameters.items()},
        None if yield_strength is None else _number("yield_strength", yield_strength, "Pa"),
        None if shear_strength is None else _number("shear_strength", shear_strength, "Pa"),
    )


def per_spot_friction(
    result: Mapping[str, Any],
    composite_height: np.ndarray,
    dx: float,
    dy: Optional[float] = None,
    *,
    model: str,
    material: Optional[Material] = None,
    composite_modulus: Optional[float] = None,
    hardness: Optional[float] = None,
    poisson_ratio: Optional[float] = None,
    periodic: bool = True,
    connectivity: int = 4,
    adhesion_energy: Optional[float] = None,
    equilibrium_distance: Optional[float] = None,
    parameters: Optional[Mapping[str, Union[float, str]]] = None,
    yield_strength: Optional[float] = None,
    shear_strength: Optional[float] = None,
) -> Dict[str, Any]:
    """Static friction of a :func:`contact` result spot by spot, as a study's ``per_spot``
    friction node: the connected contact spots of ``result["pressure"]`` (``connectivity`` 4 or
    8, wrapping around when ``periodic``), each with its load, area and paraboloid radius fitted
    to ``composite_height`` (m: the lower heights against a flat, lower + upper for two
    surfaces), and the law ``model`` (``"full_stick"``, ``"kogut_etsion"``, ``"ceb"`` or
    ``"junction_shear"`` with ``shear_strength`` τ_s in Pa) per spot; the Lennard-Jones adhesion
    across ``result["gap"]``. μ_s = ΣQ_i / (ΣP_i − F_a). Material as in :func:`static_friction`, :func:`per_spot_friction`.

    Returns ``mu_s`` (None without a compressive net force), the totals (N, m²), the adhesion
    force (N), the load beyond the law's validated range, and per spot ``spot_load_N``,
    ``spot_area_m2``, ``spot_radius_m`` (None without a convex fit) and ``spot_friction_N``.
    """
    for key in ("pressure", "gap"):
        if not isinstance(result, Mapping) or key not in result:
            raise TypeError(f"result: expected the dict of asperity.contact with '{key}'")
    x, y = _spacing(dx, dy)
    if connectivity not in (4, 8):
        raise ValueError(f"connectivity: {connectivity!r} is out of range: expected 4 or 8")
    e, h, nu = _friction_material(material, composite_modulus, hardness, poisson_ratio)
    return dict(
        _native.per_spot_friction(
            _heights("result['pressure']", result["pressure"]),
            _heights("result['gap']", result["gap"]),
            _heights("composite_height", composite_height),
            x,
            y,
            str(model),
            e,
            h,
            nu,
            bool(periodic),
            connectivity == 8,
            _native.DEFAULT_ADHESION_ENERGY if adhesion_energy is None else _number("adhesion_energy", adhesion_energy, "N/m", positive=False),
            _native.DEFAULT_EQUILIBRIUM_DISTANCE if equilibrium_distance is None else _number("equilibrium_distance", equilibrium_distance, "m"),
            *_law_options(parameters, yield_strength, shear_strength),
        )
    )


def per_summit_friction(
    result: Mapping[str, Any],
    composite_height: np.ndarray,
    dx: float,
    dy: Optional[float] = None,
    *,
    model: str = "kogut_etsion",
    material: Optional[Material] = None,
    composite_modulus: Optional[float] = None,
    hardness: Optional[float] = None,
    poisson_ratio: Optional[float] = None,
    periodic: bool = True,
    adhesion_energy: Optional[float] = None,
    equilibrium_distance: Optional[float] = None,
    parameters: Optional[Mapping[str, Union[float, str]]] = None,
    yield_strength: Optional[float] = None,
) -> Dict[str, Any]:
    """Static friction of a :func:`contact` result summit by summit, as a study's ``per_summit``
    friction node: the summits (8-neighbour maxima, periodic when ``periodic``) of
    ``composite_height`` (m: the lower heights against a flat, lower + upper for two surfaces),
    each with its radius and its interference from the solution (the deformation of both bodies
    plus the plastic penetration where the pressure is positive, minus the gap elsewhere), and the
    single-asperity laws of ``model`` (any law with them: ``"kogut_etsion"``,
    ``"chang_etsion_bogy"``, ``"full_stick"``). μ_s = ΣF_f / Σ(F_n − F_a). Material as in
    :func:`static_friction`.

    Returns ``mu_s`` (None without a compressive net force), the totals (N), the load beyond the
    laws' validated range and per summit ``summit_radius_m``, ``summit_interference_m`` (m, < 0:
    a gap), ``summit_normal_force_N``, ``summit_friction_force_N`` and
    ``summit_adhesion_force_N``.
    """
    for key in ("pressure", "gap", "deformation_lower", "plastic_penetration"):
        if not isinstance(result, Mapping) or key not in result:
            raise TypeError(f"result: expected the dict of asperity.contact with '{key}'")
    x, y = _spacing(dx, dy)
    deformation = _heights("result['deformation_lower']", result["deformation_lower"])
    if result.get("deformation_upper") is not None:
        deformation = deformation + _heights("result['deformation_upper']", result["deformation_upper"])
    e, h, nu = _friction_material(material, composite_modulus, hardness, poisson_ratio)
    law_parameters, y_strength, _ = _law_options(parameters, yield_strength, None)
    return dict(
        _native.per_summit_friction(
            _heights("composite_height", composite_height),
            _heights("result['pressure']", result["pressure"]),
            _heights("result['gap']", result["gap"]),
            deformation,
            _heights("result['plastic_penetration']", result["plastic_penetration"]),
            x,
            y,
            str(model),
            e,
            h,
            nu,
            bool(periodic),
            _native.DEFAULT_ADHESION_ENERGY if adhesion_energy is None else _number("adhesion_energy", adhesion_energy, "N/m", positive=False),
            _native.DEFAULT_EQUILIBRIUM_DISTANCE if equilibrium_distance is None else _number("equilibrium_distance", equilibrium_distance, "m"),
            law_parameters,
            y_strength,
        )
    )
