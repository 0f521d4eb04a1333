"""Argument checks of the public functions: every error names the parameter, the value given and
the expected unit or range.

A physical quantity is a plain number in SI units or a string with its unit (``"0.5 um"``,
``"20 MPa"``, ``"90 deg"``), read by the study files' own parser (``_native.parse_quantity``):
``"1.19 um"`` gives the bits a study's ``1.19 um`` gives.
"""

from __future__ import annotations

import math
import os
from typing import Any, List, Mapping, Optional, Sequence, Tuple

import numpy as np
import numpy.typing as npt

from . import _native

F64 = npt.NDArray[np.float64]

#: Dimension name (as the study format writes it) -> (SI symbol, example, accepted units).
DIMENSIONS: Mapping[str, Tuple[str, str, str]] = _native.DIMENSIONS

LENGTH = "length"
AREA = "area"
PRESSURE = "pressure"
SURFACE_ENERGY = "surface energy"
ANGLE = "angle"
INVERSE_AREA = "inverse area"
NUMBER = "dimensionless number"


def show(value: Any) -> str:
    """A value as an error message shows it: its repr (shortened) and its type."""
    text = repr(value)
    if len(text) > 80:
        text = text[:77] + "..."
    return f"{text} ({type(value).__name__})"


def with_unit(value: float, dimension: str) -> str:
    """``2e+07 Pa``, ``0.3``."""
    symbol = DIMENSIONS[dimension][0]
    return f"{value:g} {symbol}" if symbol else f"{value:g}"


def expected(dimension: str) -> str:
    """What a quantity argument takes, for messages."""
    symbol, example, _ = DIMENSIONS[dimension]
    if not symbol:
        return "a number"
    return f"a {dimension} in {symbol} (a number, or a string with its unit such as '{example}')"


def is_number(value: Any) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, (bool, np.bool_))


def quantity(
    name: str,
    value: Any,
    dimension: str,
    *,
    minimum: float = 0.0,
    minimum_inclusive: bool = False,
    maximum: float = math.inf,
    maximum_inclusive: bool = False,
) -> float:
    """``value`` in SI units of ``dimension``, finite and inside the range (default > 0)."""
    if isinstance(value, str):
        si = float(_native.parse_quantity(name, value, dimension))
        given = f"{value!r} ({with_unit(si, dimension)})"
    elif is_number(value):
        si = float(value)
        given = with_unit(si, dimension)
    else:
        raise TypeError(f"{name}: expected {expected(dimension)}, got {show(value)}")
    above = si >= minimum if minimum_inclusive else si > minimum
    below = si <= maximum if maximum_inclusive else si < maximum
    if not (math.isfinite(si) and above and below):
        raise ValueError(f"{name}: {given} is out of range: must be {range_text(dimension, minimum, minimum_inclusive, maximum, maximum_inclusive)}")
    return si


def range_text(dimension: str, minimum: float, minimum_inclusive: bool, maximum: float, maximum_inclusive: bool) -> str:
    """``finite and > 0 m``, ``in [0, 0.5)``."""
    symbol = DIMENSIONS[dimension][0]
    unit = f" {symbol}" if symbol else ""
    if maximum == math.inf:
        return f"finite and {'>=' if minimum_inclusive else '>'} {minimum:g}{unit}"
    low, high = "[" if minimum_inclusive else "(", "]" if maximum_inclusive else ")"
    return f"in {low}{minimum:g}, {maximum:g}{high}{unit}"


def optional_quantity(name: str, value: Any, dimension: str, **bounds: Any) -> Optional[float]:
    return None if value is None else quantity(name, value, dimension, **bounds)


def quantities(name: str, value: Any, dimension: str) -> List[float]:
    """One quantity or a sequence of them (a list, a tuple or a 1-D array), each > 0."""
    if isinstance(value, str) or is_number(value):
        return [quantity(f"{name}[0]", value, dimension)]
    if isinstance(value, np.ndarray) and value.ndim != 1:
        raise ValueError(f"{name}: expected one {dimension} or a 1-D sequence of them, got an array of shape {value.shape}")
    if not isinstance(value, (Sequence, np.ndarray)):
        raise TypeError(f"{name}: expected {expected(dimension)} or a sequence of them, got {show(value)}")
    if len(value) == 0:
        raise ValueError(f"{name}: expected at least one {dimension} in {DIMENSIONS[dimension][0]}, got an empty sequence")
    return [quantity(f"{name}[{i}]", v, dimension) for i, v in enumerate(value)]


def pair(name: str, value: Any, dimension: str) -> Tuple[float, float]:
    """One quantity (for x and y) or a pair ``(x, y)``, each > 0."""
    if isinstance(value, str) or is_number(value):
        x = quantity(name, value, dimension)
        return (x, x)
    if isinstance(value, (tuple, list, np.ndarray)):
        if len(value) != 2:
            raise ValueError(f"{name}: expected one {dimension} or a pair (x, y) in {DIMENSIONS[dimension][0]}, got {len(value)} values: {show(value)}")
        return (quantity(f"{name}[0]", value[0], dimension), quantity(f"{name}[1]", value[1], dimension))
    raise TypeError(f"{name}: expected {expected(dimension)} or a pair (x, y) of them, got {show(value)}")


def triple(name: str, value: Any, what: str, parts: Sequence[Tuple[str, str]]) -> Tuple[float, float, float]:
    """Three named quantities, e.g. the spectral moments ``(m0, m2, m4)``."""
    described = ", ".join(f"{label} in {DIMENSIONS[d][0] or '1'}" for label, d in parts)
    if not isinstance(value, (tuple, list, np.ndarray)) or isinstance(value, str):
        raise TypeError(f"{name}: expected {what} ({described}), got {show(value)}")
    if len(value) != 3:
        raise ValueError(f"{name}: expected {what} ({described}), got {len(value)} value(s): {show(value)}")
    a, b, c = (quantity(f"{name}[{i}] ({label})", v, d) for i, (v, (label, d)) in enumerate(zip(value, parts)))
    return (a, b, c)


def integer(name: str, value: Any, minimum: int, what: str = "an integer") -> int:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name}: expected {what} >= {minimum}, got {show(value)}")
    if int(value) < minimum:
        raise ValueError(f"{name}: {int(value)} is out of range: must be an integer >= {minimum}")
    return int(value)


def grid(name: str, value: Any) -> Tuple[int, int]:
    """A point count (square grid) or ``(nx, ny)``, each at least 2."""
    what = "a point count or (nx, ny), integers >= 2"
    if isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_)):
        n = integer(name, value, 2, what)
        return (n, n)
    if isinstance(value, (tuple, list)) and len(value) == 2:
        return (integer(f"{name}[0]", value[0], 2, what), integer(f"{name}[1]", value[1], 2, what))
    if isinstance(value, (tuple, list)):
        raise ValueError(f"{name}: expected {what}, got {len(value)} values: {show(value)}")
    raise TypeError(f"{name}: expected {what}, got {show(value)}")


def boolean(name: str, value: Any) -> bool:
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name}: expected True or False, got {show(value)}")
    return bool(value)


def choice(name: str, value: Any, options: Sequence[str]) -> str:
    if not isinstance(value, str):
        raise TypeError(f"{name}: expected one of {', '.join(repr(o) for o in options)}, got {show(value)}")
    if value not in options:
        raise ValueError(f"{name}: {value!r} is not one of: {', '.join(repr(o) for o in options)}")
    return value


def text(name: str, value: Any, what: str) -> str:
    if not isinstance(value, str):
        raise TypeError(f"{name}: expected {what}, got {show(value)}")
    return value


def path(name: str, value: Any) -> str:
    if isinstance(value, (str, os.PathLike)):
        return os.fspath(value)
    raise TypeError(f"{name}: expected a path (str or os.PathLike), got {show(value)}")


def optional_path(name: str, value: Any) -> Optional[str]:
    return None if value is None else path(name, value)


def heights(name: str, value: Any) -> F64:
    """A 2-D float64 height map in m, C-contiguous (a copy only when needed)."""
    if not isinstance(value, np.ndarray):
        raise TypeError(f"{name}: expected a 2-D NumPy array of heights in m (or a Topography), got {show(value)}")
    if value.ndim != 2:
        raise ValueError(f"{name}: expected a 2-D array [iy, ix] of heights in m, got {value.ndim} dimension(s), shape {value.shape}")
    if value.dtype.kind not in "fiu":
        raise TypeError(f"{name}: expected real heights in m, got an array of dtype {value.dtype}")
    return np.ascontiguousarray(value, dtype=np.float64)
