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
:class:`MaterialConstants`, :class:`ContactResult` (with :class:`LoadStep` and :class:`ContactStep`),
:class:`FrictionLaw` (with :class:`FrictionLawParameter`), :class:`StaticFrictionRow`,
:class:`PerSpotResult`, :class:`PerSummitResult` and :class:`StudyCounts`. A bad argument raises ``TypeError`` or ``ValueError`` naming the parameter, the value and
its expected unit or range; a value that is possible but probably in the wrong unit, or that a
study would flag, raises a :class:`PlausibilityWarning`. Every computation releases the GIL.
"""

from __future__ import annotations

from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _args, _native
from ._args import F64
from ._contact import contact, material
from ._friction import friction_laws, per_spot_friction, per_summit_friction, static_friction
from ._native import StudyError
from ._results import (
    Acf,
    ContactResult,
    ContactStep,
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
    "ContactStep",
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
    grid: Union[None, int, Tuple[int, int]] = None,
    size: Union[None, float, str, Tuple[Union[float, str], Union[float, str]]] = None,
    seed: int = 1,
    short_wavelength_cutoff: Optional[Union[float, str]] = None,
    threshold: float = 0.2,
    spectrum: str = "self_affine",
    extrapolation: str = "zero",
) -> Tuple[F64, float, float, Dict[str, Any]]:
    """A synthetic twin of measured surfaces (complete maps: :class:`Topography` objects or
    ``(heights, dx, dy)`` in m) on ``grid`` over ``size`` (m), at Sq ``sq`` (m, or
    ``"measured"``). Returns ``(heights, dx, dy, info)``; ``info`` is keyed by the names of the
    twin's columns in a study's ``surfaces`` table (``twin_sq_m``, ``twin_hurst``, …;
    ``twin_warnings`` a list of sentences).

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
    maps = _twin_maps(measured)
    checked_grid = None if grid is None else _args.grid("grid", grid)
    checked_size = None if size is None else _args.pair("size", size, _args.LENGTH)
    cutoff = _args.optional_quantity("short_wavelength_cutoff", short_wavelength_cutoff, _args.LENGTH)
    target = None if isinstance(sq, str) and sq == "measured" else _args.quantity("sq", sq, _args.LENGTH)
    kind = _args.choice("spectrum", spectrum, ["self_affine", "measured"])
    tail = _args.choice("extrapolation", extrapolation, ["zero", "power_law"])
    checked_seed = _args.integer("seed", seed, 0, "a seed")
    if kind == "measured":
        return _native.spectrum_twin(maps, target, checked_grid, checked_size, checked_seed, cutoff, tail)
    if tail != "zero":
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
        checked_seed,
        cutoff,
        _args.quantity("threshold", threshold, _args.NUMBER, maximum=1.0),
    )


def _twin_maps(measured: Sequence[Union[Topography, Tuple[F64, float, float]]]) -> List[Tuple[F64, float, float]]:
    """The measured maps of a twin as ``(heights, dx, dy)``, each checked."""
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
    return maps

