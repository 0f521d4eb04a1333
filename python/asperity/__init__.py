"""asperity: reproducible rough-surface contact and static-friction studies, from Python.

Studies: :func:`run`, :func:`plan`, :func:`validate` (a broken study raises :class:`StudyError`;
a run returns a :class:`RunResult`).

Surfaces: :class:`Topography` (a height map with its scale, periodicity and provenance; its
:meth:`~Topography.statistics`, :meth:`~Topography.psd`, :meth:`~Topography.acf`,
:meth:`~Topography.material_ratio` and :meth:`~Topography.summits`), :func:`read_topography`,
:func:`read_line_scan` (a :class:`LineScan`), :func:`topography_format`,
:func:`surface_statistics`, :func:`remove_form`, :func:`gaussian_filter`, :func:`fill_missing`,
:func:`synthetic_surface`, :func:`synthetic_twin`.

Contact and friction: :func:`material`, :func:`contact`, :func:`friction_laws`,
:func:`static_friction`, :func:`per_spot_friction`, :func:`per_summit_friction`.

SI units throughout (metres, pascals); a quantity may also be a string with its unit
(``"0.5 um"``, ``"20 MPa"``, ``"90 deg"``), read as a study file reads it. Every array function
takes a :class:`Topography` or ``(heights, dx, dy)``. Results are dicts typed by the
``TypedDict`` classes of this module, so a type checker sees their keys:
:class:`SurfaceStatistics`, :class:`Psd`, :class:`Acf`, :class:`MaterialRatio`, :class:`Summits`,
:class:`MaterialConstants`, :class:`ContactResult` (with :class:`LoadStep`),
:class:`FrictionLaw` (with :class:`FrictionLawParameter`), :class:`StaticFrictionRow`,
:class:`PerSpotResult`, :class:`PerSummitResult` and :class:`StudyCounts`. A bad argument raises ``TypeError`` or ``ValueError`` naming the parameter, the value and
its expected unit or range; a value that is possible but probably in the wrong unit, or that a
study would flag, raises a :class:`PlausibilityWarning`. Every computation releases the GIL.
"""

from __future__ import annotations

from typing import Any, Dict, Optional, Sequence, Tuple, Union

from . import _args, _native
from ._args import F64
from ._contact import contact, material
from ._friction import friction_laws, per_spot_friction, per_summit_friction, static_friction
from ._native import StudyError
from ._results import (
    Acf,
    ContactResult,
    FrictionLaw,
    FrictionLawParameter,
    LoadStep,
    MaterialConstants,
    MaterialRatio,
    PerSpotResult,
    PerSummitResult,
    Psd,
    StaticFrictionRow,
    StudyCounts,
    Summits,
    SurfaceStatistics,
)
from ._study import RunResult, plan, run, validate
from ._surface import (
    fill_missing,
    gaussian_filter,
    read_line_scan,
    read_topography,
    remove_form,
    surface_statistics,
    synthetic_surface,
    topography_format,
)
from ._topography import LineScan, Topography, as_topography
from ._warnings import PlausibilityWarning

__all__ = [
    "StudyError",
    "PlausibilityWarning",
    "RunResult",
    "run",
    "plan",
    "validate",
    "Topography",
    "LineScan",
    "read_topography",
    "read_line_scan",
    "topography_format",
    "surface_statistics",
    "remove_form",
    "gaussian_filter",
    "fill_missing",
    "synthetic_surface",
    "synthetic_twin",
    "material",
    "contact",
    "friction_laws",
    "static_friction",
    "per_spot_friction",
    "per_summit_friction",
    "Acf",
    "ContactResult",
    "FrictionLaw",
    "FrictionLawParameter",
    "LoadStep",
    "MaterialConstants",
    "MaterialRatio",
    "PerSpotResult",
    "PerSummitResult",
    "Psd",
    "StaticFrictionRow",
    "StudyCounts",
    "Summits",
    "SurfaceStatistics",
]

__version__: str = _native.TOOL_VERSION


def synthetic_twin(
    measured: Sequence[Union[Topography, Tuple[F64, float, float]]],
    *,
    sq: Union[float, str],
    grid: Union[int, Tuple[int, int]],
    size: Union[float, str, Tuple[Union[float, str], Union[float, str]]],
    seed: int = 1,
    short_wavelength_cutoff: Optional[Union[float, str]] = None,
    threshold: float = 0.2,
) -> Tuple[F64, float, float, Dict[str, Any]]:
    """A synthetic twin of measured surfaces (complete maps: :class:`Topography` objects or
    ``(heights, dx, dy)`` in m): their texture (correlation lengths at ACF ``threshold``, Hurst
    exponent) fitted against Sq and predicted at ``sq`` (m), generated on ``grid`` over ``size``
    (m). Returns ``(heights, dx, dy, prediction)``."""
    if isinstance(measured, (str, bytes, Topography)) or not isinstance(measured, Sequence):
        raise TypeError(f"measured: expected a list of Topography objects or (heights, dx, dy) tuples, got {_args.show(measured)}")
    maps = []
    for i, m in enumerate(measured):
        if isinstance(m, Topography):
            maps.append((m.heights, m.dx, m.dy))
        elif isinstance(m, tuple) and len(m) == 3:
            t, _ = as_topography(f"measured[{i}]", m[0], m[1], m[2])
            maps.append((t.heights, t.dx, t.dy))
        else:
            raise TypeError(f"measured[{i}]: expected a Topography or (heights, dx, dy), got {_args.show(m)}")
    return _native.synthetic_twin(
        maps,
        _args.quantity("sq", sq, _args.LENGTH),
        _args.grid("grid", grid),
        _args.pair("size", size, _args.LENGTH),
        _args.integer("seed", seed, 0, "a seed"),
        _args.optional_quantity("short_wavelength_cutoff", short_wavelength_cutoff, _args.LENGTH),
        _args.quantity("threshold", threshold, _args.NUMBER, maximum=1.0),
    )

