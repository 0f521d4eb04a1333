"""Surfaces: readers, statistics, form removal, filters, filling, synthetic surfaces."""

from __future__ import annotations

import warnings
from typing import Any, Dict, Optional, Tuple, Union, overload

import numpy as np

from . import _args, _native
from ._args import F64
from ._plausibility import spacing_sentences
from ._results import SurfaceStatistics
from ._study import PathLike
from ._topography import LineScan, Topography, as_topography
from ._warnings import warn

Length = Union[float, str]
Lengths = Union[float, str, Tuple[Union[float, str], Union[float, str]]]

_UNIT_SOURCE = {"file": "file", "study": "given", "assumed": "assumed"}


def topography_format(path: PathLike) -> Optional[str]:
    """The reader asperity would use for ``path`` (magic bytes, then extension), or None."""
    return _native.topography_format(_args.path("path", path))


def _read(path: PathLike, pixel_size: Optional[Lengths], size: Optional[Lengths], override_file_spacing: bool, channel: Optional[str], height_unit: Optional[Length]) -> Dict[str, Any]:
    unit = None
    if height_unit is not None:
        if isinstance(height_unit, str) and not any(c.isdigit() for c in height_unit):
            height_unit = f"1 {height_unit.strip()}"
        unit = _args.quantity("height_unit", height_unit, _args.LENGTH)
    d = _native.read_topography(
        _args.path("path", path),
        None if pixel_size is None else _args.pair("pixel_size", pixel_size, _args.LENGTH),
        None if size is None else _args.pair("size", size, _args.LENGTH),
        _args.boolean("override_file_spacing", override_file_spacing),
        None if channel is None else _args.text("channel", channel, "a channel name (str)"),
        unit,
    )
    warn(d["flags"])
    return dict(d)


def read_topography(
    path: PathLike,
    pixel_size: Optional[Lengths] = None,
    size: Optional[Lengths] = None,
    *,
    override_file_spacing: bool = False,
    channel: Optional[str] = None,
    height_unit: Optional[Length] = None,
) -> Topography:
    """Read an areal topography file (every format of ``asperity inspect``) as a
    :class:`Topography`, with a study's rules for the scale.

    The spacing is never guessed: a file that does not state it needs ``pixel_size`` (dx, dy) or
    ``size`` (Lx, Ly of the whole map), in m or as strings with units (``"0.5 um"``); one that
    does must agree with them unless ``override_file_spacing``. ``height_unit`` is the length one
    stored value stands for (``"um"``, ``"nm"``, ``"0.1 nm"``, or ``"m"`` to confirm metres) for
    a file that states none; without it such a file is read as metres with a
    :class:`PlausibilityWarning`. ``channel`` picks a channel by name (default: the height
    channel; ``Topography.channels`` lists the file's). A line-scan file is read by
    :func:`read_line_scan`.
    """
    d = _read(path, pixel_size, size, override_file_spacing, channel, height_unit)
    if "x" in d:
        warnings.warn(
            f"{path}: read_topography of a line scan is deprecated: use read_line_scan, which returns a LineScan",
            DeprecationWarning,
            stacklevel=2,
        )
        return _line_scan(d)  # type: ignore[return-value]
    t = Topography._owning(
        d["heights"],
        d["dx"],
        d["dy"],
        False,
        metadata=d["metadata"],
        channel=d["channel"],
        channels=d["channels"],
        spacing_source="file" if d["spacing_from_file"] else "given",
        height_unit_source=_UNIT_SOURCE[d["height_unit_source"]],
    )
    warn(spacing_sentences(t.dx, t.dy))
    return t


def _line_scan(d: Dict[str, Any]) -> LineScan:
    return LineScan(
        d["x"],
        d["heights"],
        d["metadata"],
        d["channel"],
        d["channels"],
        "file" if d["spacing_from_file"] else "given",
        _UNIT_SOURCE[d["height_unit_source"]],
    )


def read_line_scan(
    path: PathLike,
    pixel_size: Optional[Length] = None,
    size: Optional[Length] = None,
    *,
    override_file_spacing: bool = False,
    channel: Optional[str] = None,
    height_unit: Optional[Length] = None,
) -> LineScan:
    """Read a line-scan (profile) file as a :class:`LineScan`: positions ``x`` and ``heights``
    in m. ``pixel_size`` (dx) or ``size`` (the scan length) calibrate a file without positions;
    the other arguments as in :func:`read_topography`. An areal map raises ``ValueError``."""
    d = _read(path, pixel_size, size, override_file_spacing, channel, height_unit)
    if "x" not in d:
        raise ValueError(f"path: {path} holds an areal map, not a line scan: read it with read_topography")
    return _line_scan(d)


def surface_statistics(heights: Union[Topography, F64], dx: Optional[Length] = None, dy: Optional[Length] = None, *, periodic: Optional[bool] = None) -> SurfaceStatistics:
    """The statistics of the ``surfaces`` table for a :class:`Topography` (or a height map in m,
    NaN missing, at spacing ``dx``, ``dy`` in m): ISO 25178-2 amplitude, hybrid, functional and
    volume parameters, spectral parameters (Sal, Str, Std, Hurst, moments; complete maps only)
    and summit statistics, keyed by column name with the SI unit (``sq_m``, ``sdq``, ``m2``…).
    ``periodic`` (default: the topography's; False for an array) for synthetic (periodic) maps."""
    t, _ = as_topography("heights", heights, dx, dy)
    return t.statistics(periodic=periodic)


@overload
def remove_form(heights: Topography, dx: None = None, dy: None = None, *, degree: int = 1) -> Tuple[Topography, float]: ...
@overload
def remove_form(heights: F64, dx: Length, dy: Optional[Length] = None, *, degree: int = 1) -> Tuple[F64, float]: ...
def remove_form(heights: Union[Topography, F64], dx: Optional[Length] = None, dy: Optional[Length] = None, *, degree: int = 1) -> Tuple[Union[Topography, F64], float]:
    """Remove the least-squares Legendre polynomial form of total degree ``degree`` (1: plane);
    returns the residual (a Topography for a Topography, else heights in m) and its rms (m)."""
    t, given = as_topography("heights", heights, dx, dy)
    residual, rms = _native.remove_form(t.heights, t.dx, t.dy, _args.integer("degree", degree, 0, "a polynomial degree"))
    return (t.with_heights(residual) if given else residual), rms


@overload
def gaussian_filter(heights: Topography, dx: None = None, dy: None = None, *, kind: str, cutoff: Length, long_cutoff: Optional[Length] = None) -> Topography: ...
@overload
def gaussian_filter(heights: F64, dx: Length, dy: Optional[Length] = None, *, kind: str, cutoff: Length, long_cutoff: Optional[Length] = None) -> F64: ...
def gaussian_filter(
    heights: Union[Topography, F64],
    dx: Optional[Length] = None,
    dy: Optional[Length] = None,
    *,
    kind: str,
    cutoff: Length,
    long_cutoff: Optional[Length] = None,
) -> Union[Topography, F64]:
    """ISO 16610-61 areal Gaussian filter: ``kind="low"`` (S-filter, λs = ``cutoff``),
    ``"high"`` (L-filter, λc = ``cutoff``) or ``"band"`` (λs = ``cutoff``, λc = ``long_cutoff``);
    cut-off wavelengths in m (or strings such as ``"25 um"``)."""
    t, given = as_topography("heights", heights, dx, dy)
    kind = _args.choice("kind", kind, ("low", "high", "band"))
    long = _args.optional_quantity("long_cutoff", long_cutoff, _args.LENGTH)
    filtered = _native.gaussian_filter(t.heights, t.dx, t.dy, kind, _args.quantity("cutoff", cutoff, _args.LENGTH), long)
    return t.with_heights(filtered) if given else filtered


@overload
def fill_missing(heights: Topography, dx: None = None, dy: None = None) -> Tuple[Topography, int]: ...
@overload
def fill_missing(heights: F64, dx: Length, dy: Optional[Length] = None) -> Tuple[F64, int]: ...
def fill_missing(heights: Union[Topography, F64], dx: Optional[Length] = None, dy: Optional[Length] = None) -> Tuple[Union[Topography, F64], int]:
    """Fill the missing (NaN) points by harmonic interpolation of the measured ones; returns the
    filled map (a Topography for a Topography, else heights in m) and the number of points
    filled."""
    t, given = as_topography("heights", heights, dx, dy)
    filled, count = _native.fill_missing(t.heights, t.dx, t.dy)
    return (t.with_heights(filled) if given else filled), count


def synthetic_surface(
    grid: Union[int, Tuple[int, int]],
    size: Lengths,
    *,
    sq: Length,
    hurst: float,
    correlation_length: Length,
    seed: int = 1,
    short_wavelength_cutoff: Optional[Length] = None,
    anisotropy: Optional[Tuple[float, Union[float, str]]] = None,
) -> Topography:
    """A periodic self-affine Gaussian surface, the one a study's ``synthetic`` surface with the
    same parameters makes: ``grid`` points (n, or (nx, ny)), ``size`` (L or (Lx, Ly), m), ``sq``
    (m), Hurst exponent in (0, 1], roll-off ``correlation_length`` (m), optional
    ``short_wavelength_cutoff`` (m) and ``anisotropy`` (aspect ratio ≥ 1, lay angle in rad or
    ``"30 deg"``). Lengths are in m or strings with units (``"0.4 um"``). Returns a periodic
    :class:`Topography` (unpacking it as ``heights, dx, dy`` is deprecated)."""
    aniso = None
    if anisotropy is not None:
        if not isinstance(anisotropy, (tuple, list)) or len(anisotropy) != 2:
            raise TypeError(f"anisotropy: expected (aspect ratio >= 1, lay angle in rad or e.g. '30 deg'), got {_args.show(anisotropy)}")
        aniso = (
            _args.quantity("anisotropy[0] (aspect ratio)", anisotropy[0], _args.NUMBER),
            _args.quantity("anisotropy[1] (lay angle)", anisotropy[1], _args.ANGLE, minimum=-np.inf),
        )
    heights, dx, dy = _native.synthetic_surface(
        _args.grid("grid", grid),
        _args.pair("size", size, _args.LENGTH),
        _args.quantity("sq", sq, _args.LENGTH),
        _args.quantity("hurst", hurst, _args.NUMBER, maximum=1.0, maximum_inclusive=True),
        _args.quantity("correlation_length", correlation_length, _args.LENGTH),
        _args.integer("seed", seed, 0, "a seed"),
        _args.optional_quantity("short_wavelength_cutoff", short_wavelength_cutoff, _args.LENGTH),
        aniso,
    )
    t = Topography._owning(heights, dx, dy, True)
    warn(spacing_sentences(dx, dy))
    return t
